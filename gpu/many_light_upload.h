// The many-light samplers' inputs on the GPU: the VPLs and what a sampler's prepare() built on
// the CPU (SamplerInputs, core/manylight/sampler_inputs.h: the tree, the per-block cuts and their
// guides, the mock cut, SamplerParams), uploaded into the storage buffers that
// MANY_LIGHT_BUFFERS(first) declares (core/manylight/many_light_layout.h) for
// gpu/shaders/indirect_sampler.glsl to read.
#pragma once
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "core/manylight/sampler_inputs.h"
#include "core/vpl/vpl.h"

namespace sst::gpu {

// VPLs in GPU layout, index for index.
std::vector<GpuVpl> pack_vpls(std::span<const Vpl> vpls);

}  // namespace sst::gpu

#ifdef SST_HAVE_VULKAN
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// The seven buffers, in MANY_LIGHT_BUFFERS order. An array a sampler does not use (or an empty
// VPL set or tree) is a 16-byte dummy: Vulkan has no empty buffers, and the shaders never index
// it. A buffer beyond the device's storage-buffer limit is an sst::Error naming it (GpuBuffer).
class GpuManyLightInputs {
 public:
  static constexpr uint32_t kBufferCount = kManyLightBufferCount;

  GpuManyLightInputs(const VulkanContext& context, const SamplerInputs& inputs);
  GpuManyLightInputs(const GpuManyLightInputs&) = delete;
  GpuManyLightInputs& operator=(const GpuManyLightInputs&) = delete;

  // Bindings first .. first + 6 of a shader that declares MANY_LIGHT_BUFFERS(first).
  std::vector<const GpuBuffer*> buffers() const;
  const SamplerParams& params() const { return params_; }
  // Device memory of the seven buffers, in bytes (as allocated).
  size_t bytes() const;

 private:
  SamplerParams params_;
  std::unique_ptr<GpuBuffer> params_buffer_, vpls_, nodes_, cut_nodes_, cut_sizes_, guides_, mock_cut_;
};

}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
