#include "core/metrics/ssim.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/metrics/same_shape.h"

namespace sst {
namespace {

constexpr int kTaps = 2 * kSsimRadius + 1;
constexpr double kC1 = 0.01 * 0.01;  // (K1 * data_range)^2
constexpr double kC2 = 0.03 * 0.03;  // (K2 * data_range)^2
constexpr int kMoments = 5;          // x, y, xx, yy, xy

using Plane = std::vector<double>;

// scipy.ndimage._gaussian_kernel1d(sigma=1.5, radius=5), normalised to sum 1.
std::array<double, kTaps> gaussian_window() {
  std::array<double, kTaps> w{};
  double sum = 0.0;
  for (int i = 0; i < kTaps; ++i) {
    const double x = i - kSsimRadius;
    w[i] = std::exp(-0.5 / (1.5 * 1.5) * x * x);
    sum += w[i];
  }
  for (double& v : w) v /= sum;
  return w;
}

// scipy's 'reflect' (half-sample symmetric: d c b a | a b c d | d c b a), any distance out.
int reflect(int i, int n) {
  const int period = 2 * n;
  i %= period;
  if (i < 0) i += period;
  return i < n ? i : period - 1 - i;
}

// out[x] = sum_k w[k] * taps[k][x], the taps paired around the centre as scipy's correlate1d
// does for symmetric kernels. x innermost, one store per pixel: the loop vectorises.
void filter_taps(const std::array<const double*, kTaps>& taps, const std::array<double, kTaps>& w, int width,
                 double* out) {
  for (int x = 0; x < width; ++x) {
    double sum = taps[kSsimRadius][x] * w[kSsimRadius];
    for (int j = 1; j <= kSsimRadius; ++j)
      sum += (taps[kSsimRadius + j][x] + taps[kSsimRadius - j][x]) * w[kSsimRadius + j];
    out[x] = sum;
  }
}

// Horizontally filtered moments (x, y, xx, yy, xy) of source rows, in a ring of kTaps slots:
// the rows one output row needs lie within kTaps consecutive indices, so they never share a
// slot, and walking output rows downwards computes each source row once.
class RowCache {
 public:
  RowCache(const Image& a, const Image& b, int channel, const std::array<double, kTaps>& w)
      : a_(a),
        b_(b),
        channel_(channel),
        w_(w),
        source_x_(a.width + 2 * kSsimRadius),
        rows_(size_t(kTaps) * kMoments * a.width) {
    cached_.fill(-1);
    for (int i = 0; i < int(source_x_.size()); ++i) source_x_[i] = reflect(i - kSsimRadius, a.width);
    for (auto& s : products_) s.resize(source_x_.size());
  }

  // Moment q of source row y.
  const double* row(int y, int q) {
    const int slot = y % kTaps;
    if (cached_[slot] != y) compute(y, slot);
    return &rows_[(size_t(slot) * kMoments + q) * a_.width];
  }

 private:
  void compute(int y, int slot) {
    for (size_t i = 0; i < source_x_.size(); ++i) {
      const double va = a_.at(source_x_[i], y, channel_), vb = b_.at(source_x_[i], y, channel_);
      products_[0][i] = va;
      products_[1][i] = vb;
      products_[2][i] = va * va;
      products_[3][i] = vb * vb;
      products_[4][i] = va * vb;
    }
    for (int q = 0; q < kMoments; ++q) {
      const double* in = products_[q].data() + kSsimRadius;
      std::array<const double*, kTaps> taps;
      for (int k = 0; k < kTaps; ++k) taps[k] = in + (k - kSsimRadius);
      filter_taps(taps, w_, a_.width, &rows_[(size_t(slot) * kMoments + q) * a_.width]);
    }
    cached_[slot] = y;
  }

  const Image& a_;
  const Image& b_;
  int channel_;
  const std::array<double, kTaps>& w_;
  std::vector<int> source_x_;                           // reflected column of each padded column
  std::array<std::vector<double>, kMoments> products_;  // one padded source row
  std::vector<double> rows_;                            // kTaps slots x kMoments x width
  std::array<int, kTaps> cached_;                       // source row held by each slot
};

double ssim_value(double ux, double uy, double uxx, double uyy, double uxy) {
  const double vx = uxx - ux * ux, vy = uyy - uy * uy, vxy = uxy - ux * uy;
  return ((2.0 * ux * uy + kC1) * (2.0 * vxy + kC2)) / ((ux * ux + uy * uy + kC1) * (vx + vy + kC2));
}

// Vertical pass and the SSIM formula for the output rows [y0, y1) into map (row-major, full
// size). Every value depends only on its inputs, so how rows are split among threads changes
// no bit of the result.
void ssim_rows(const Image& a, const Image& b, int channel, const std::array<double, kTaps>& w, int y0,
               int y1, Plane& map) {
  const int width = a.width;
  RowCache cache(a, b, channel, w);
  std::array<std::vector<double>, kMoments> acc;
  for (auto& row : acc) row.resize(width);
  for (int y = y0; y < y1; ++y) {
    for (int q = 0; q < kMoments; ++q) {
      std::array<const double*, kTaps> taps;
      for (int k = 0; k < kTaps; ++k) taps[k] = cache.row(reflect(y + k - kSsimRadius, a.height), q);
      filter_taps(taps, w, width, acc[q].data());
    }
    double* out = &map[size_t(y) * width];
    for (int x = 0; x < width; ++x)
      out[x] = ssim_value(acc[0][x], acc[1][x], acc[2][x], acc[3][x], acc[4][x]);
  }
}

Plane ssim_plane(const Image& a, const Image& b, int channel) {
  const auto w = gaussian_window();
  Plane map(size_t(a.width) * a.height);
  // Strips of at least 64 rows keep the 10 rows each strip filters twice a small overhead.
  tbb::parallel_for(tbb::blocked_range<int>(0, a.height, 128), [&](const tbb::blocked_range<int>& rows) {
    ssim_rows(a, b, channel, w, rows.begin(), rows.end(), map);
  });
  return map;
}

bool window_fits(const Image& a) { return a.width >= kTaps && a.height >= kTaps; }

}  // namespace

double ssim_channel(const Image& a, const Image& b, int channel) {
  require_same_shape(a, b);
  if (!window_fits(a)) return std::numeric_limits<double>::quiet_NaN();
  const Plane map = ssim_plane(a, b, channel);
  // Row sums in a fixed order, so the mean does not depend on the thread count.
  double sum = 0.0;
  for (int y = kSsimRadius; y < a.height - kSsimRadius; ++y) {
    double row = 0.0;
    for (int x = kSsimRadius; x < a.width - kSsimRadius; ++x) row += map[size_t(y) * a.width + x];
    sum += row;
  }
  const double count = double(a.width - 2 * kSsimRadius) * double(a.height - 2 * kSsimRadius);
  return sum / count;
}

double ssim(const Image& a, const Image& b) {
  require_same_shape(a, b);
  double sum = 0.0;
  for (int c = 0; c < a.channels; ++c) sum += ssim_channel(a, b, c);
  return sum / a.channels;
}

Image ssim_map(const Image& a, const Image& b) {
  require_same_shape(a, b);
  Image out(a.width, a.height, a.channels);
  if (a.pixel_count() == 0) return out;
  for (int c = 0; c < a.channels; ++c) {
    const Plane map = ssim_plane(a, b, c);
    for (size_t p = 0; p < out.pixel_count(); ++p) out.data[p * a.channels + c] = float(map[p]);
  }
  return out;
}

}  // namespace sst
