#include "gpu/restir_gi_vulkan.h"

#include "core/pt/path_tracer.h"
#include "gpu/gpu_render_context.h"
#include "gpu/path_trace_pass.h"

namespace sst::gpu {

void VulkanRestirGi::release_device() {
  direct_.reset();
  pipelines_.reset();
  if (history_) park_restir_history(*history_);
}

std::vector<uint8_t> VulkanRestirGi::save_history() const {
  return history_ ? restir_history_bytes(download_restir_history(*history_)) : std::vector<uint8_t>{};
}

void VulkanRestirGi::restore_history(std::span<const uint8_t> bytes, bool posed) {
  if (!history_) history_ = std::make_unique<GpuRestirHistory>();
  restore_restir_history(*history_, restir_history_from_bytes(bytes), posed);
}

FrameOutput VulkanRestirGi::render(const RenderContext& ctx, const GpuRenderContext& gpu, StageTimer& timer) {
  if (!pipelines_) {
    timer.time("shader_compile", [&] {
      direct_ = make_path_trace_pipeline(gpu.vulkan(), gpu.lights(), gpu.top_level());
      pipelines_ = make_restir_pipelines(gpu);
    });
  }
  if (!history_) history_ = std::make_unique<GpuRestirHistory>();
  GpuPathTraceResult direct = timer.time("render", [&] {
    return render_path_tracer(gpu, *direct_, ctx.camera, ctx.width, ctx.height, ctx.options.seed, ctx.options.spp,
                              restir_gi_direct_params(), render_flags(ctx.options));
  });
  FrameOutput frame = std::move(direct.frame);
  const RestirGiParams& p = method_.gi_params();
  run_restir(ctx, gpu, *pipelines_, RestirKind::indirect, restir_gi_push(ctx, gpu.ray_epsilon(), p),
             restir_gi_reuse(p), *history_, "restir_gi", timer, frame);
  frame.method_counters["gpu_ms"]["render"] = direct.gpu_ms;
  return frame;
}

}  // namespace sst::gpu
