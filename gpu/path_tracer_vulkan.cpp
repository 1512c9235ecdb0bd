#include "gpu/path_tracer_vulkan.h"

#include "gpu/gpu_render_context.h"
#include "gpu/path_trace_pass.h"

namespace sst::gpu {

FrameOutput VulkanPathTracer::render(const RenderContext& ctx, const GpuRenderContext& gpu, StageTimer& timer) {
  auto pipeline = timer.time("shader_compile", [&] { return make_path_trace_pipeline(gpu.vulkan()); });
  GpuPathTraceResult r = timer.time("render", [&] {
    return render_path_tracer(gpu, *pipeline, ctx.camera, ctx.width, ctx.height, ctx.options.seed,
                              ctx.options.spp, method_.tracer_params(), ctx.options.diffuse_only);
  });
  r.frame.method_counters["gpu_ms"] = {{"render", r.gpu_ms}};
  r.frame.method_counters["gpu"] = {{"render_dispatches", r.dispatches}};
  return std::move(r.frame);
}

}  // namespace sst::gpu
