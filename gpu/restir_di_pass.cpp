#include "gpu/restir_di_pass.h"

#include <utility>
#include <vector>

#include "core/restir/restir_di.h"
#include "gpu/gpu_buffer.h"
#include "gpu/gpu_render_context.h"

namespace sst::gpu {

std::unique_ptr<RestirDiPipelines> make_restir_di_pipelines(const GpuRenderContext& gpu) {
  auto out = std::make_unique<RestirDiPipelines>();
  for (int stage = 0; stage < 4; ++stage)
    out->stages[size_t(stage)] =
        gpu.make_pipeline("restir_di_" + std::to_string(stage), GpuRenderContext::kSceneBufferCount + 7,
                          uint32_t(sizeof(glsl::RestirDiPush)), gpu.lights().sampler_specialization());
  return out;
}

void add_restir_direct(const RenderContext& ctx, const GpuRenderContext& gpu, RestirDiPipelines& pipelines,
                       StageTimer& timer, FrameOutput& frame, GpuRestirHistory& history) {
  const VulkanContext& context = gpu.vulkan();
  const size_t pixels = size_t(ctx.width) * size_t(ctx.height);
  const std::string size = std::to_string(ctx.width) + "x" + std::to_string(ctx.height);
  auto surfaces_of = [&] { return make_buffer(context, pixels, sizeof(glsl::RestirSurface), "restir_di: first hits of " + size); };
  auto reservoirs_of = [&] {
    return make_buffer(context, pixels, sizeof(glsl::RestirReservoir), "restir_di: reservoirs of " + size);
  };
  const RestirDiPush probe = restir_push(ctx, gpu.ray_epsilon(), 0u, 0u, false);
  if (!history.surfaces || !restir_history_usable(true, history.view_params, probe)) {
    history.surfaces = surfaces_of();
    history.reservoirs = reservoirs_of();
    history.view = make_buffer(context, 1, sizeof(glsl::ViewParams), "restir_di: the history's view");
    history.valid = false;
  }
  std::unique_ptr<GpuBuffer> surfaces = surfaces_of(), in = reservoirs_of(), out = reservoirs_of();
  auto texels = make_buffer(context, pixels, sizeof(glsl::RestirTexel), "restir_di: per-pixel sums of " + size);
  const uint32_t groups_x = (uint32_t(ctx.width) + 7) / 8, groups_y = (uint32_t(ctx.height) + 7) / 8;
  double gpu_ms = 0.0;
  timer.time("restir_di", [&] {
    auto run = [&](int stage, const glsl::RestirDiPush& push) {
      std::vector<const GpuBuffer*> buffers = gpu.scene_buffers();
      buffers.insert(buffers.end(), {surfaces.get(), in.get(), out.get(), texels.get(), history.surfaces.get(),
                                     history.reservoirs.get(), history.view.get()});
      gpu_ms += pipelines.stages[size_t(stage)]->dispatch(buffers, &push, groups_x, groups_y);
    };
    for (int round = 0; round < ctx.options.spp; ++round) {
      // As add_restir_direct: only a frame's first round continues the previous frame's last.
      const bool temporal = round == 0 && ctx.options.restir.temporal && history.valid;
      const RestirDiPush push = restir_push(ctx, gpu.ray_epsilon(), uint32_t(round), 0u, temporal);
      // Each stage writes `out`, which the next reads as `in`.
      run(0, push);
      std::swap(in, out);
      if (temporal) {
        run(1, push);
        std::swap(in, out);
      }
      for (int pass = 0; pass < ctx.options.restir.spatial_passes; ++pass) {
        run(2, restir_push(ctx, gpu.ray_epsilon(), uint32_t(round), uint32_t(pass), temporal));
        std::swap(in, out);
      }
      run(3, push);
      // This round is the next one's history.
      std::swap(history.surfaces, surfaces);
      std::swap(history.reservoirs, in);
      history.view_params = push.view;
      history.view->upload(std::span<const glsl::ViewParams>(&history.view_params, 1));
      history.valid = true;
    }
  });
  std::vector<glsl::RestirTexel> sums(pixels);
  texels->download(std::span<glsl::RestirTexel>(sums));
  add_restir_sums(sums, ctx.options.spp, frame);
  frame.method_counters["gpu_ms"]["restir_di"] = gpu_ms;
}

}  // namespace sst::gpu
