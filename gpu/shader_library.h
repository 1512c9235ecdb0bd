// The compute shaders of the Vulkan backend: gpu/shaders/*.comp, compiled to SPIR-V by glslc at
// build time and embedded in the binary (cmake/embed_spirv.cmake), so that sst-render needs no
// files beside it. A shader is named by its file stem ("rng_test" for rng_test.comp).
#pragma once
#include <cstdint>
#include <span>
#include <string_view>

namespace sst::gpu {

// The SPIR-V words of shader `name`; empty when no such shader was built (or glslc was missing).
std::span<const uint32_t> embedded_spirv(std::string_view name);

}  // namespace sst::gpu
