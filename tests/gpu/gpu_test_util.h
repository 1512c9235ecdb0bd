// What the GPU tests share: skipping, with the reason, where a shader cannot run (no Vulkan
// device, or the build had no glslc), so that the same tests pass on lavapipe, on a real GPU, and
// skip cleanly elsewhere.
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "core/render/backend.h"
#include "gpu/shader_library.h"

namespace sst::test {

// "" when `shader` can run here, else why not.
inline std::string gpu_unavailable(std::string_view shader) {
  std::string reason;
  if (list_vulkan_devices(&reason).empty()) return "no Vulkan device: " + reason;
  if (gpu::embedded_spirv(shader).empty()) return "shader " + std::string(shader) + " is not built in (no glslc)";
  return "";
}

}  // namespace sst::test

#define SKIP_WITHOUT_GPU(shader)                                  \
  do {                                                            \
    std::string why = ::sst::test::gpu_unavailable(shader); \
    if (!why.empty()) GTEST_SKIP() << why;                        \
  } while (0)
