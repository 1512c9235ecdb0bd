// Statistics for tests that must not flake: chi-square against a critical value at a tiny
// significance level (fixed seeds make each test deterministic; the level makes a real bug,
// not chance, the likely reason for a failure).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/image/image.h"

namespace sst::test {

// Pearson's statistic; bins whose expected count is below 5 are pooled into one.
inline double chi_square_statistic(const std::vector<double>& observed, const std::vector<double>& expected,
                                   int* degrees_of_freedom) {
  double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
  int bins = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5.0) {
      pooled_o += observed[i];
      pooled_e += expected[i];
      continue;
    }
    chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pooled_e >= 5.0) {
    chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++bins;
  } else if (pooled_o > 0.0 && pooled_e == 0.0) {
    chi2 = INFINITY;  // observed where nothing may be: a hard failure
  }
  *degrees_of_freedom = std::max(1, bins - 1);
  return chi2;
}

// Upper critical value of the chi-square distribution at significance 1e-6 (Wilson-Hilferty).
inline double chi_square_critical_1e6(int dof) {
  const double z = 4.753;  // standard normal quantile of 1 - 1e-6
  double k = double(dof);
  double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

// Per k x k block and channel of a w x h image: the mean over renders with independent seeds of
// the block's mean, and the variance of that mean (from the spread over the seeds), for Welch
// t-tests between two renderers that do not rely on the renders' own variance estimates.
class SeedBlockMeans {
 public:
  SeedBlockMeans(int width, int height, int block)
      : width_(width), height_(height), block_(block), blocks_x_(width / block), count_(blocks_x_ * (height / block) * 3),
        sum_(count_, 0.0), sum2_(count_, 0.0) {}
  void add(const Image& img) {
    std::vector<double> block(count_, 0.0);
    for (int y = 0; y < blocks_y() * block_; ++y)
      for (int x = 0; x < blocks_x_ * block_; ++x)
        for (int c = 0; c < 3; ++c)
          block[((y / block_) * blocks_x_ + x / block_) * 3 + c] +=
              img.data[(size_t(y) * size_t(width_) + size_t(x)) * img.channels + c] / double(block_ * block_);
    for (int b = 0; b < count_; ++b) sum_[b] += block[b], sum2_[b] += block[b] * block[b];
    ++renders_;
  }
  int size() const { return count_; }
  double mean(int b) const { return sum_[b] / renders_; }
  double variance_of_mean(int b) const {
    double m = mean(b);
    return std::max(0.0, (sum2_[b] / renders_ - m * m) * renders_ / (renders_ - 1)) / renders_;
  }
  double image_mean() const {
    double m = 0.0;
    for (int b = 0; b < count_; ++b) m += mean(b) / count_;
    return m;
  }
  double summed_variance() const {
    double v = 0.0;
    for (int b = 0; b < count_; ++b) v += variance_of_mean(b);
    return v;
  }

 private:
  int blocks_y() const { return height_ / block_; }
  int width_, height_, block_, blocks_x_, count_;
  std::vector<double> sum_, sum2_;
  int renders_ = 0;
};

// Welch's t of every block of `a` against `b`: the largest |t| and how many exceed `threshold`.
struct BlockTTest {
  double largest = 0.0;
  int failures = 0;
};
inline BlockTTest block_t_test(const SeedBlockMeans& a, const SeedBlockMeans& b, double threshold) {
  BlockTTest r;
  for (int i = 0; i < a.size(); ++i) {
    double sd = std::sqrt(a.variance_of_mean(i) + b.variance_of_mean(i));
    double t = sd > 0.0 ? (a.mean(i) - b.mean(i)) / sd : (a.mean(i) == b.mean(i) ? 0.0 : INFINITY);
    r.largest = std::max(r.largest, std::abs(t));
    r.failures += std::abs(t) > threshold;
  }
  return r;
}

}  // namespace sst::test
