// The statistics of the distribution check (distribution_check.h): an image reduced to what the
// tests compare (block and image means, pixel noise), its error energy, the mean and variance of
// a value over seeds, and the two tests, the pooled two-sample t-test and the same-seed test
// against a margin. Functions of images and numbers only: the baseline's files and JSON
// (distribution_baseline.h) and the check's verdicts (distribution_check.cpp) build on them.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/image/image.h"

namespace sst::distribution {

constexpr int kChannels = 3;

// One seed's image reduced to what the tests compare.
struct Reduction {
  std::vector<double> blocks;             // [block * 3 + channel]: the block's mean
  std::array<double, kChannels> image{};  // the whole image's mean
  double log_noise = 0.0;                 // pixel_noise()
};

// The number of blocks of `block` pixels that cover `pixels`, the last one partial.
int blocks_across(int pixels, int block);

// The log of the median over pixels and channels of the squared differences between horizontal
// and vertical neighbours: the image's pixel-to-pixel noise. Unlike the error energy it ignores
// what whole regions share (a VPL set's offset, a radiance cache's blotches), which varies from
// seed to seed by far more than a 50% rise in pixel variance.
double pixel_noise(const Image& im);

// The block means (blocks of `block` x `block` pixels), image means and pixel noise of `im`.
Reduction reduce(const Image& im, int block);

// The median over pixels and channels of (image - mean)^2, times `scale`, as a log. The median,
// not the mean: one firefly would otherwise carry a seed's energy (and the spread of the energies
// over seeds), and the log because energies are closer to normal in it.
double log_energy(const Image& im, const Image& mean, double scale);

bool all_finite(const Image& im);

struct MeanVariance {
  double mean = 0.0;
  double variance = 0.0;  // unbiased
};

MeanVariance mean_variance(const std::vector<double>& v);

// The mean and variance over seeds of one value of their reductions.
template <class Value>
MeanVariance over_seeds(const std::vector<Reduction>& reductions, Value value) {
  std::vector<double> v;
  for (const Reduction& r : reductions) v.push_back(value(r));
  return mean_variance(v);
}

struct TTest {
  double t = 0.0;
  double p = 1.0;
};

// Pooled two-sample t-test of a fresh sample (mean, variance, n) against the baseline's;
// `one_sided`: only a larger fresh mean is significant. A non-finite fresh mean gets t NaN and
// p 0, so that it fails.
TTest pooled_t(const MeanVariance& base, int n_base, const MeanVariance& fresh, int n_fresh, bool one_sided);

// The same-seed test of one value: are the fresh values' log ratios to the baseline's, seed by
// seed, further from 0 than `margin` beyond their noise? A t-test of the mean ratio against the
// margin (n - 1 degrees of freedom): with the same random numbers the ratios are nearly equal
// over seeds, so a change of a few percent stands out even where the seed-to-seed spread is far
// larger; where a change has made the random numbers differ, the ratios spread like the estimates
// and the test is as valid, and weaker. The margin keeps float rounding (another CPU's Embree
// kernels or libm) from counting as a change. `one_sided`: only a rise counts.
struct MarginTest {
  double change = 0.0;  // the mean log ratio
  TTest t;
};

MarginTest margin_t(const std::vector<double>& log_ratios, double margin, bool one_sided);

// A mean as it enters a log ratio: values at or below `floor` (a small fraction of the image's
// mean) count as the floor, so that a block that turned black is a large finite change.
inline double log_above(double v, double floor) { return std::log(std::max(v, floor)); }

}  // namespace sst::distribution
