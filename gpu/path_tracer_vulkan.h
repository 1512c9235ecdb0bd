// PathTracer on the Vulkan backend: the whole frame in gpu/shaders/pt.comp (gpu/path_trace_pass.h),
// timed as stage "render" like the CPU's (after "shader_compile"), with the GPU's own time beside it.
#pragma once
#include "core/pt/path_tracer.h"
#include "gpu/vulkan_method.h"

namespace sst::gpu {

class VulkanPathTracer final : public VulkanMethod {
 public:
  explicit VulkanPathTracer(const PathTracer& method) : method_(method) {}
  FrameOutput render(const RenderContext& context, const GpuRenderContext& gpu, StageTimer& timer) override;

 private:
  const PathTracer& method_;
};

}  // namespace sst::gpu
