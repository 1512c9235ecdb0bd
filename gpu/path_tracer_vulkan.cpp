#include "gpu/path_tracer_vulkan.h"

#include "gpu/gpu_render_context.h"
#include "gpu/path_trace_pass.h"

namespace sst::gpu {

FrameOutput VulkanPathTracer::render(const RenderContext& ctx, const GpuRenderContext& gpu, StageTimer& timer) {
  GpuPathTraceResult r;
  if (ctx.options.gpu_paths == "wavefront") {
    auto pipelines = timer.time("shader_compile", [&] { return make_path_wavefront_pipelines(gpu); });
    r = timer.time("render", [&] {
      return render_path_tracer_wavefront(gpu, *pipelines, ctx.camera, ctx.width, ctx.height, ctx.options.seed,
                                          ctx.options.spp, method_.tracer_params(), render_flags(ctx.options));
    });
  } else {
    auto pipeline = timer.time("shader_compile",
                               [&] { return make_path_trace_pipeline(gpu.vulkan(), gpu.lights(), gpu.top_level()); });
    r = timer.time("render", [&] {
      return render_path_tracer(gpu, *pipeline, ctx.camera, ctx.width, ctx.height, ctx.options.seed, ctx.options.spp,
                                method_.tracer_params(), render_flags(ctx.options));
    });
  }
  nlohmann::json gpu_ms = {{"render", r.gpu_ms}};
  for (const auto& [stage, ms] : r.stage_ms) gpu_ms[stage] = ms;
  r.frame.method_counters["gpu_ms"] = gpu_ms;
  r.frame.method_counters["gpu"] = {{"render_dispatches", r.dispatches}, {"paths", ctx.options.gpu_paths}};
  return std::move(r.frame);
}

}  // namespace sst::gpu
