#include "core/eval/distribution_stats.h"

#include <algorithm>

#include "core/math/student_t.h"

namespace sst::distribution {
namespace {

// The median of `squares` (reordered), 0 when empty.
double median_of(std::vector<double>& squares) {
  if (squares.empty()) return 0.0;
  auto middle = squares.begin() + squares.size() / 2;
  std::nth_element(squares.begin(), middle, squares.end());
  return *middle;
}

}  // namespace

int blocks_across(int pixels, int block) { return (pixels + block - 1) / block; }

double pixel_noise(const Image& im) {
  std::vector<double> squares;
  squares.reserve(im.pixel_count() * 2 * kChannels);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      for (int c = 0; c < kChannels; ++c) {
        const double v = im.at(x, y, c);
        if (x + 1 < im.width) squares.push_back((im.at(x + 1, y, c) - v) * (im.at(x + 1, y, c) - v));
        if (y + 1 < im.height) squares.push_back((im.at(x, y + 1, c) - v) * (im.at(x, y + 1, c) - v));
      }
  return std::log(std::max(median_of(squares), 1e-300));
}

Reduction reduce(const Image& im, int block) {
  const int bx = blocks_across(im.width, block), by = blocks_across(im.height, block);
  Reduction r;
  r.blocks.assign(size_t(bx) * by * kChannels, 0.0);
  std::vector<double> counts(size_t(bx) * by, 0.0);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const size_t b = size_t(y / block) * bx + size_t(x / block);
      counts[b] += 1.0;
      for (int c = 0; c < kChannels; ++c) {
        r.blocks[b * kChannels + c] += im.at(x, y, c);
        r.image[c] += im.at(x, y, c);
      }
    }
  for (size_t b = 0; b < counts.size(); ++b)
    for (int c = 0; c < kChannels; ++c) r.blocks[b * kChannels + c] /= counts[b];
  for (int c = 0; c < kChannels; ++c) r.image[c] /= double(im.pixel_count());
  r.log_noise = pixel_noise(im);
  return r;
}

double log_energy(const Image& im, const Image& mean, double scale) {
  std::vector<double> squares;
  squares.reserve(im.pixel_count() * kChannels);
  for (size_t i = 0; i < im.pixel_count(); ++i)
    for (int c = 0; c < kChannels; ++c) {
      const double d = double(im.data[i * im.channels + c]) - double(mean.data[i * mean.channels + c]);
      squares.push_back(d * d);
    }
  return std::log(std::max(scale * median_of(squares), 1e-300));
}

bool all_finite(const Image& im) {
  return std::all_of(im.data.begin(), im.data.end(), [](float v) { return std::isfinite(v); });
}

MeanVariance mean_variance(const std::vector<double>& v) {
  MeanVariance m;
  for (double x : v) m.mean += x;
  m.mean /= double(v.size());
  for (double x : v) m.variance += (x - m.mean) * (x - m.mean);
  m.variance = v.size() > 1 ? m.variance / double(v.size() - 1) : 0.0;
  return m;
}

TTest pooled_t(const MeanVariance& base, int n_base, const MeanVariance& fresh, int n_fresh, bool one_sided) {
  const double df = double(n_base + n_fresh - 2);
  const double pooled = ((n_base - 1) * base.variance + (n_fresh - 1) * fresh.variance) / df;
  const double se = std::sqrt(pooled * (1.0 / n_base + 1.0 / n_fresh));
  const double diff = fresh.mean - base.mean;
  TTest r;
  if (!std::isfinite(diff)) r.t = NAN;
  else if (se > 0.0) r.t = diff / se;
  else r.t = diff == 0.0 ? 0.0 : std::copysign(INFINITY, diff);
  if (std::isnan(r.t)) r.p = 0.0;  // a non-finite fresh value fails
  else r.p = one_sided ? student_t_upper_p(r.t, df) : student_t_two_sided_p(r.t, df);
  return r;
}

MarginTest margin_t(const std::vector<double>& log_ratios, double margin, bool one_sided) {
  const MeanVariance m = mean_variance(log_ratios);
  const double n = double(log_ratios.size());
  MarginTest r;
  r.change = m.mean;
  const double excess = (one_sided ? m.mean : std::abs(m.mean)) - margin;
  if (!std::isfinite(m.mean)) {
    r.t = {NAN, 0.0};
  } else if (excess > 0.0) {
    const double se = std::sqrt(m.variance / n);
    r.t.t = se > 0.0 ? excess / se : INFINITY;
    const double upper = student_t_upper_p(r.t.t, n - 1.0);
    r.t.p = one_sided ? upper : std::min(1.0, 2.0 * upper);
  }
  return r;
}

}  // namespace sst::distribution
