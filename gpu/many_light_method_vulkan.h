// ManyLightMethod on the Vulkan backend: the same stages as ManyLightMethod::render, with the VPLs
// generated, radix and perfect light trees built, and the pixels sampled on the GPU. The per-block
// cuts (rtslc, hybrid) and agglomerative trees are built on the CPU by the sampler's own prepare()
// and uploaded (the record says where each ran under "built_on").
#pragma once
#include "core/manylight/many_light_method.h"
#include "gpu/vulkan_method.h"

namespace sst::gpu {

class VulkanManyLightMethod final : public VulkanMethod {
 public:
  // Prepares the method's sampler on this backend's VPLs and trees, so it is not const.
  explicit VulkanManyLightMethod(ManyLightMethod& method) : method_(method) {}
  FrameOutput render(const RenderContext& context, const GpuRenderContext& gpu, StageTimer& timer) override;

 private:
  ManyLightMethod& method_;
};

}  // namespace sst::gpu
