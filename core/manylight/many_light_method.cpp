#include "core/manylight/many_light_method.h"

#include <atomic>
#include <mutex>

#include "core/manylight/direct_pass.h"
#include "core/manylight/shading_point.h"
#include "core/pt/path_batch.h"
#include "core/render/pixel_loop.h"
#include "core/brsm/brsm_generator.h"
#include "core/vpl/vpl_clamp.h"
#include "core/vpl/vpl_ply.h"

namespace sst {

namespace {

// Per-pixel sums of one frame, merged into the frame's counters at the end.
struct Accumulators {
  std::atomic<uint64_t> nodes{0}, shadow_rays{0}, indirect_samples{0};
  std::mutex histogram_mutex;
  std::vector<uint64_t> depth_histogram = std::vector<uint64_t>(65, 0);  // last bin: 64 or more
};

}  // namespace

void write_many_light_pixel(const ManyLightPixelSums& sums, int spp, int x, int y, FrameOutput& frame, Image& variance,
                            Image& traversal_depth) {
  const float inv = 1.0f / float(spp);
  write_path_means(sums.path, inv, x, y, frame);
  // Variance of the pixel mean (sample variance / spp), for per-pixel z-tests.
  const vec3 mean = sums.path.indirect * inv;
  vec3 var = spp > 1 ? glm::max(sums.indirect2 * inv - mean * mean, vec3(0.0f)) / float(spp - 1) : vec3(0.0f);
  variance.set_rgb(x, y, var);
  traversal_depth.at(x, y, 0) =
      sums.indirect_samples ? float(sums.nodes) / float(sums.indirect_samples) : 0.0f;
}

EmissionFocus view_emission_focus(const RenderContext& ctx, float view_distance, float directional_focus) {
  EmissionFocus focus = emission_focus_none();
  if (!(directional_focus > 0.0f) || !(view_distance > 0.0f)) return focus;
  focus.center = ctx.camera.generate(0.5f * float(ctx.width), 0.5f * float(ctx.height)).origin;
  focus.radius = directional_focus * view_distance;
  return focus;
}

ManyLightMethod::ManyLightMethod(VplParams vpl_params, nlohmann::json params, std::unique_ptr<IndirectSampler> sampler)
    : vpl_params_(vpl_params), params_(std::move(params)), sampler_(std::move(sampler)) {
  validate(vpl_params_);
}

FrameOutput ManyLightMethod::render(const RenderContext& ctx, StageTimer& timer) {
  FrameOutput frame;
  frame.allocate(ctx.width, ctx.height);
  Image variance(ctx.width, ctx.height), depth(ctx.width, ctx.height, 1);

  VplStats vpl_stats;
  const float view_distance = median_view_distance(ctx);
  VplSet vpls = timer.time("vpl_generation", [&] {
    const EmissionFocus focus = view_emission_focus(ctx, view_distance, vpl_params_.directional_focus);
    if (vpl_params_.vpl_source == "brsm")
      return generate_brsm_vpls(ctx.scene, ctx.accel, ctx.lights, vpl_params_,
                                view_params(ctx.camera, ctx.width, ctx.height, ctx.options.seed), ctx.options.seed,
                                ctx.options.diffuse_only, &vpl_stats, focus);
    return generate_vpls(ctx.scene, ctx.accel, ctx.lights, vpl_params_, ctx.options.seed, ctx.options.diffuse_only,
                         &vpl_stats, focus);
  });
  if (!vpl_params_.export_vpls.empty()) write_vpls_ply(vpl_params_.export_vpls, vpls);
  VplLighting lighting{ctx, vpls, vpl_stats.clamp_distance, vpl_stats.clamp_per_depth, view_distance};
  frame.method_counters["vpl"] = to_json(vpl_stats);
  frame.method_counters["view_distance"] = view_distance;
  sampler_->prepare(lighting, timer, frame.method_counters);

  const bool own_direct = sampler_->estimates_direct() && !restir_direct(ctx.options);
  const PathConfig direct_pass = many_light_direct_config(
      own_direct || restir_direct(ctx.options), ctx.options.diffuse_only, vpl_params_.clamp_compensation ? vpl_params_.light_bounces() : 0,
      vpl_params_.vpl_min_bounces, vpl_stats.clamp_distance, vpl_stats.clamp_per_depth);
  Accumulators acc;
  const int spp = ctx.options.spp;
  timer.time("sampling", [&] {
    for_each_tile(ctx.width, ctx.height, ctx.quiet, "sampling", frame.counters, [&](const Tile& tile, RayCounters& rc) {
      std::vector<ManyLightPixelSums> sums(size_t(tile.pixels()));
      std::vector<uint32_t> depths;
      // The direct light of the tile's camera paths (in batches), then each path's indirect
      // estimate at its first hit, with the sampler where the path left it.
      trace_tile_paths(ctx, direct_pass, tile, rc, [&](int pixel, int, const Ray& ray, PathState& path) {
        const int x = tile.x0 + pixel % tile.width(), y = tile.y0 + pixel / tile.width();
        PathSample& d = path.result;
        ManyLightPixelSums& sum = sums[size_t(pixel)];
        vec3 value(0.0f);
        if (d.depth > 0.0f) {
          ShadingPoint sp = shading_point(path.first_hit, ray.direction, d.depth, ctx.options.diffuse_only, x, y);
          if (own_direct) d.direct += sampler_->estimate_direct(ctx, sp, path.ps, rc);
          IndirectEstimate e = sampler_->estimate(sp, path.ps);
          rc.shadow_rays += e.shadow_rays;
          sum.nodes += e.nodes_visited;
          ++sum.indirect_samples;
          depths.push_back(e.nodes_visited);
          value = e.value;
        }
        // The compensation path's light (zero without clamp compensation) is part of the estimate.
        value += d.indirect;
        if (!is_finite(d.direct) || !is_finite(value)) {
          ++rc.nonfinite_samples;
          return;
        }
        sum.path.direct += d.direct;
        sum.path.indirect += value;
        sum.indirect2 += value * value;
        sum.path.albedo += d.albedo;
        sum.path.normal += d.normal;
        sum.path.depth += d.depth;
      });
      for (int pixel = 0; pixel < tile.pixels(); ++pixel) {
        const ManyLightPixelSums& sum = sums[size_t(pixel)];
        write_many_light_pixel(sum, spp, tile.x0 + pixel % tile.width(), tile.y0 + pixel / tile.width(), frame,
                               variance, depth);
        acc.nodes += sum.nodes;
        acc.indirect_samples += sum.indirect_samples;
      }
      std::lock_guard lock(acc.histogram_mutex);
      for (uint32_t v : depths) ++acc.depth_histogram[std::min<uint32_t>(v, 64)];
    });
  });
  frame.extra_layers = {{"indirect_variance", variance}, {"traversal_depth", depth}};
  uint64_t samples = acc.indirect_samples.load();
  frame.method_counters["indirect_samples"] = samples;
  frame.method_counters["nodes_visited_mean"] = samples ? double(acc.nodes.load()) / double(samples) : 0.0;
  frame.method_counters["nodes_visited_histogram"] = acc.depth_histogram;
  return frame;
}

}  // namespace sst
