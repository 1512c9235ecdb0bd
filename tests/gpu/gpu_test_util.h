// What the GPU tests share: skipping, with the reason, where a shader cannot run (no Vulkan
// device, or the build had no glslc), so that the same tests pass on lavapipe, on a real GPU, and
// skip cleanly elsewhere.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>

#include "core/image/image.h"

#include "core/pipeline/backend.h"
#include "gpu/shader_library.h"

namespace sst::test {

// "" when `shader` can run here, else why not.
inline std::string gpu_unavailable(std::string_view shader) {
  std::string reason;
  if (list_vulkan_devices(&reason).empty()) return "no Vulkan device: " + reason;
  if (gpu::embedded_spirv(shader).empty()) return "shader " + std::string(shader) + " is not built in (no glslc)";
  return "";
}

// The mean of every channel of every pixel.
inline double image_mean(const Image& img) {
  double s = 0.0;
  for (float v : img.data) s += v;
  return img.data.empty() ? 0.0 : s / double(img.data.size());
}

// RMSE of the GPU image against the CPU's, as a fraction of the CPU image's mean magnitude
// (absolute when the CPU image is black): the bar for "the same image" is 1e-3.
inline double relative_rmse(const Image& gpu, const Image& cpu) {
  double s = 0.0, m = 0.0;
  for (size_t i = 0; i < cpu.data.size(); ++i) {
    s += double(gpu.data[i] - cpu.data[i]) * (gpu.data[i] - cpu.data[i]);
    m += std::abs(double(cpu.data[i]));
  }
  double n = double(cpu.data.size()), rmse = std::sqrt(s / n);
  return m > 0.0 ? rmse / (m / n) : rmse;
}

}  // namespace sst::test

#define SKIP_WITHOUT_GPU(shader)                                  \
  do {                                                            \
    std::string why = ::sst::test::gpu_unavailable(shader); \
    if (!why.empty()) GTEST_SKIP() << why;                        \
  } while (0)
