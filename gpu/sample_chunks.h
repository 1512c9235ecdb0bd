// A frame's samples are rendered in several dispatches of consecutive sample indices, so that no
// single dispatch runs long enough to meet the fence timeout (or a desktop GPU's watchdog): the
// first dispatch takes one sample per pixel, and each next one is sized from the last one's time
// (the first may include the driver's shader compilation). On lavapipe every dispatch takes one
// sample: it ends a shader invocation's loops after 65535 iterations in all (bvh_traverse.h), so
// each sample gets a fresh invocation.
#pragma once
#include <algorithm>
#include <cmath>

namespace sst::gpu {

class SampleChunks {
 public:
  SampleChunks(int spp, bool one_per_dispatch, double target_ms = 500.0)
      : spp_(spp), one_per_dispatch_(one_per_dispatch), target_ms_(target_ms) {}

  bool done() const { return offset_ >= spp_; }
  int offset() const { return offset_; }  // first sample index of the next dispatch
  // Samples of the next dispatch.
  int size() const {
    int remaining = spp_ - offset_;
    if (offset_ == 0 || one_per_dispatch_ || !(ms_per_sample_ > 0.0)) return std::min(1, remaining);
    double fit = std::floor(target_ms_ / ms_per_sample_);
    return std::clamp(int(std::min(fit, double(remaining))), 1, std::max(remaining, 1));
  }
  // After the dispatch of size() samples, with its GPU time.
  void advance(double gpu_ms) {
    int n = size();
    ms_per_sample_ = gpu_ms / double(n);
    offset_ += n;
  }

 private:
  int spp_;
  bool one_per_dispatch_;
  double target_ms_;
  int offset_ = 0;
  double ms_per_sample_ = 0.0;
};

}  // namespace sst::gpu
