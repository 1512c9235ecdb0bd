#include "gpu/restir_pass.h"

#include <utility>
#include <vector>

#include "core/restir/restir_di.h"
#include "gpu/gpu_render_context.h"

namespace sst::gpu {

std::unique_ptr<RestirPipelines> make_restir_pipelines(const GpuRenderContext& gpu) {
  auto out = std::make_unique<RestirPipelines>();
  for (int stage = 0; stage < 6; ++stage)
    out->stages[size_t(stage)] =
        gpu.make_pipeline("restir_" + std::to_string(stage), GpuRenderContext::kSceneBufferCount + 7,
                          uint32_t(sizeof(glsl::RestirPush)), gpu.lights().sampler_specialization());
  return out;
}

RestirHistory download_restir_history(const GpuRestirHistory& history) {
  if (!history.valid) return history.parked;
  RestirHistory h;
  const size_t pixels = size_t(history.view_params.width) * size_t(history.view_params.height);
  h.surfaces.resize(pixels);
  h.reservoirs.resize(pixels);
  history.surfaces->download(std::span<glsl::RestirSurface>(h.surfaces));
  history.reservoirs->download(std::span<glsl::RestirReservoir>(h.reservoirs));
  h.view = history.view_params;
  h.space = history.space;
  h.valid = true;
  h.posed = history.posed;
  return h;
}

void park_restir_history(GpuRestirHistory& history) {
  restore_restir_history(history, download_restir_history(history), true);
}

void restore_restir_history(GpuRestirHistory& history, RestirHistory host, bool posed) {
  history.parked = std::move(host);
  history.parked.posed = posed;
  history.surfaces.reset();
  history.reservoirs.reset();
  history.view.reset();
  history.valid = false;
  history.posed = false;
}

void run_restir(const RenderContext& ctx, const GpuRenderContext& gpu, RestirPipelines& pipelines, RestirKind kind,
                const RestirPush& base, const RestirReuse& reuse, GpuRestirHistory& history, const char* stage_name,
                StageTimer& timer, FrameOutput& frame) {
  const VulkanContext& context = gpu.vulkan();
  const size_t pixels = size_t(ctx.width) * size_t(ctx.height);
  const std::string size = std::to_string(ctx.width) + "x" + std::to_string(ctx.height);
  auto surfaces_of = [&] {
    return make_buffer(context, pixels, sizeof(glsl::RestirSurface), std::string(stage_name) + ": first hits of " + size);
  };
  auto reservoirs_of = [&] {
    return make_buffer(context, pixels, sizeof(glsl::RestirReservoir), std::string(stage_name) + ": reservoirs of " + size);
  };
  const RestirSampleSpace space = restir_sample_space(ctx.lights.packed().header);
  if (!history.surfaces || !restir_history_usable(true, history.view_params, history.space, base, space)) {
    history.surfaces = surfaces_of();
    history.reservoirs = reservoirs_of();
    history.view = make_buffer(context, 1, sizeof(glsl::ViewParams), std::string(stage_name) + ": the history's view");
    history.valid = false;
    // A history parked on the host while the device was made again comes back where it serves.
    const RestirHistory& h = history.parked;
    if (restir_history_usable(h.valid, h.view, h.space, base, space)) {
      history.surfaces->upload(std::span<const glsl::RestirSurface>(h.surfaces));
      history.reservoirs->upload(std::span<const glsl::RestirReservoir>(h.reservoirs));
      history.view_params = h.view;
      history.view->upload(std::span<const glsl::ViewParams>(&history.view_params, 1));
      history.space = h.space;
      history.valid = true;
    }
    history.posed = history.posed || h.posed;
    history.parked = RestirHistory{};
  }
  std::unique_ptr<GpuBuffer> surfaces = surfaces_of(), in = reservoirs_of(), out = reservoirs_of();
  auto texels = make_buffer(context, pixels, sizeof(glsl::RestirTexel), std::string(stage_name) + ": sums of " + size);
  const uint32_t groups_x = (uint32_t(ctx.width) + 7) / 8, groups_y = (uint32_t(ctx.height) + 7) / 8;
  const int initial = kind == RestirKind::direct ? 0 : 4;
  double gpu_ms = 0.0;
  timer.time(stage_name, [&] {
    auto run = [&](int stage, const glsl::RestirPush& push) {
      std::vector<const GpuBuffer*> buffers = gpu.scene_buffers();
      buffers.insert(buffers.end(), {surfaces.get(), in.get(), out.get(), texels.get(), history.surfaces.get(),
                                     history.reservoirs.get(), history.view.get()});
      gpu_ms += pipelines.stages[size_t(stage)]->dispatch(buffers, &push, groups_x, groups_y);
    };
    for (int round = 0; round < ctx.options.spp; ++round) {
      // As run_restir on the CPU: only a frame's first round continues the previous frame's last.
      const bool temporal = round == 0 && reuse.temporal && restir_history_kept(history.posed, reuse) && history.valid;
      const RestirPush push = restir_round_push(base, uint32_t(round), 0u, temporal, history.posed);
      // Each stage writes `out`, which the next reads as `in`.
      run(initial, push);
      std::swap(in, out);
      if (temporal && history.posed && kind == RestirKind::indirect) {
        run(5, push);  // the history's reservoirs validated into `out`
        std::swap(history.reservoirs, out);
      }
      if (temporal) {
        run(1, push);
        std::swap(in, out);
      }
      for (int pass = 0; pass < reuse.spatial_passes; ++pass) {
        run(2, restir_round_push(base, uint32_t(round), uint32_t(pass), temporal, false));
        std::swap(in, out);
      }
      run(3, push);
      // This round is the next one's history.
      std::swap(history.surfaces, surfaces);
      std::swap(history.reservoirs, in);
      history.view_params = push.view;
      history.view->upload(std::span<const glsl::ViewParams>(&history.view_params, 1));
      history.space = space;
      history.valid = true;
      history.posed = false;
    }
  });
  std::vector<glsl::RestirTexel> sums(pixels);
  texels->download(std::span<glsl::RestirTexel>(sums));
  add_restir_sums(sums, ctx.options.spp, kind, frame);
  frame.method_counters["gpu_ms"][stage_name] = gpu_ms;
}

void add_restir_direct(const RenderContext& ctx, const GpuRenderContext& gpu, RestirPipelines& pipelines,
                       StageTimer& timer, FrameOutput& frame, GpuRestirHistory& history) {
  run_restir(ctx, gpu, pipelines, RestirKind::direct, restir_di_push(ctx, gpu.ray_epsilon()),
             restir_reuse(ctx.options.restir), history, "restir_di", timer, frame);
}

}  // namespace sst::gpu
