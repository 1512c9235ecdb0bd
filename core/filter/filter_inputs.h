// The C++ side of the filter kernels' hooks (filter_kernel_common.h): the images a kernel reads,
// as interleaved float arrays (core/image's layout, which the shaders' storage buffers share).
#pragma once
#include "core/math/cpu_gpu.h"

namespace sst {

struct FilterInputs {
  const float* color = nullptr;     // RGB: the image being filtered, or the low-resolution image
  const float* variance = nullptr;  // 1 channel
  const float* moments = nullptr;   // 2 channels
  const float* history = nullptr;   // 1 channel
  const float* depth = nullptr;     // 1 channel
  const float* normal = nullptr;    // RGB
  const float* low_depth = nullptr;
  const float* low_normal = nullptr;
};

inline vec3 filter_load3(const float* image, int i) { return vec3(image[3 * i], image[3 * i + 1], image[3 * i + 2]); }
inline vec2 filter_load2(const float* image, int i) { return vec2(image[2 * i], image[2 * i + 1]); }

}  // namespace sst

#define FILTER_CTX_PARAM const ::sst::FilterInputs &fi,
#define FILTER_CTX fi,
#define FILTER_COLOR(i) ::sst::filter_load3(fi.color, i)
#define FILTER_VARIANCE(i) fi.variance[i]
#define FILTER_MOMENTS(i) ::sst::filter_load2(fi.moments, i)
#define FILTER_HISTORY(i) fi.history[i]
#define FILTER_DEPTH(i) fi.depth[i]
#define FILTER_NORMAL(i) ::sst::filter_load3(fi.normal, i)
#define FILTER_LOW_DEPTH(i) fi.low_depth[i]
#define FILTER_LOW_NORMAL(i) ::sst::filter_load3(fi.low_normal, i)
