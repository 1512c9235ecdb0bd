// A frame's samples are rendered in several dispatches of consecutive sample indices, so that no
// single dispatch runs long enough to meet the fence timeout (or a desktop GPU's watchdog): the
// first dispatch takes one sample per pixel, and the rest are sized from its measured time.
#pragma once
#include <algorithm>
#include <cmath>

namespace sst::gpu {

// Samples for the next dispatch, given the GPU time one sample per pixel took and those left.
inline int next_sample_chunk(double ms_per_sample, int remaining, double target_ms = 500.0) {
  if (!(ms_per_sample > 0.0)) return remaining;
  double fit = std::floor(target_ms / ms_per_sample);
  return std::clamp(int(std::min(fit, double(remaining))), 1, std::max(remaining, 1));
}

}  // namespace sst::gpu
