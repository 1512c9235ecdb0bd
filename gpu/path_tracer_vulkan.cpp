// PathTracer on the Vulkan backend: the whole frame in gpu/shaders/pt.comp (gpu/path_trace_pass.h),
// timed as stage "render" like the CPU's (after "shader_compile"), with the GPU's own time beside it.
#include "core/render/path_tracer.h"
#include "gpu/gpu_render_context.h"
#include "gpu/path_trace_pass.h"

namespace sst {

FrameOutput PathTracer::render_vulkan(const RenderContext& ctx, StageTimer& timer) {
  auto pipeline = timer.time("shader_compile", [&] { return gpu::make_path_trace_pipeline(ctx.gpu->vulkan()); });
  gpu::GpuPathTraceResult r = timer.time("render", [&] {
    return gpu::render_path_tracer(*ctx.gpu, *pipeline, ctx.camera, ctx.width, ctx.height, ctx.options.seed,
                                   ctx.options.spp, params_, ctx.options.diffuse_only);
  });
  r.frame.method_counters["gpu_ms"] = {{"render", r.gpu_ms}};
  r.frame.method_counters["gpu"] = {{"render_dispatches", r.dispatches}};
  return std::move(r.frame);
}

}  // namespace sst
