#include "core/pt/path_tracer.h"

#include "core/pt/path_batch.h"
#include "core/render/pixel_loop.h"

namespace sst {

PathConfig path_tracer_config(const PathTracerParams& params, const RenderOptions& options) {
  return path_config_for(params.max_bounces, params.rr_min_bounces, render_flags(options));
}

PathSample trace_path(const RenderContext& ctx, const PathTracerParams& params, Ray ray, PixelSampler& sampler,
                      RayCounters& counters, Surface* first_hit) {
  PathCounters rays = path_counters();
  Surface s;
  bool hit = false;
  PathSample out = trace_path(ctx.scene, ctx.lights.packed(), ctx.accel, ray.origin, ray.direction,
                              path_tracer_config(params, ctx.options),
                              sampler, rays, s, hit);
  counters.primary_rays += rays.primary_rays;
  counters.shadow_rays += rays.shadow_rays;
  counters.bounce_rays += rays.bounce_rays;
  if (first_hit && hit) *first_hit = s;
  return out;
}

void write_path_means(const PathSample& sum, float inv_spp, int x, int y, FrameOutput& frame) {
  frame.direct.set_rgb(x, y, sum.direct * inv_spp);
  frame.indirect.set_rgb(x, y, sum.indirect * inv_spp);
  frame.color.set_rgb(x, y, (sum.direct + sum.indirect) * inv_spp);
  frame.albedo.set_rgb(x, y, sum.albedo * inv_spp);
  vec3 n = sum.normal;
  frame.normal.set_rgb(x, y, glm::length(n) > 0.0f ? glm::normalize(n) : n);
  frame.depth.at(x, y, 0) = sum.depth * inv_spp;
}

PathTracer::PathTracer(const PathTracerParams& params) : params_(params) {
  if (params_.max_bounces < 0) throw Error("max_bounces must be >= 0 (got " + std::to_string(params_.max_bounces) + ")");
  if (params_.max_bounces > 1024) throw Error("max_bounces must be <= 1024");
  if (params_.rr_min_bounces < 0) throw Error("rr_min_bounces must be >= 0");
}

nlohmann::json PathTracer::params() const { return params_to_json(params_); }

FrameOutput PathTracer::render(const RenderContext& ctx, StageTimer& timer) {
  FrameOutput frame;
  frame.allocate(ctx.width, ctx.height);
  const float inv_spp = 1.0f / float(ctx.options.spp);
  const PathConfig cfg = path_tracer_config(params_, ctx.options);
  timer.time("render", [&] {
    for_each_tile(ctx.width, ctx.height, ctx.quiet, "pt", frame.counters, [&](const Tile& tile, RayCounters& counters) {
      std::vector<PathSample> sums(size_t(tile.pixels()));
      trace_tile_paths(ctx, cfg, tile, counters, [&](int pixel, int, const Ray&, PathState& path) {
        const PathSample& p = path.result;
        // A NaN or Inf sample is a bug to find, not a pixel to show: drop and count it.
        if (!is_finite(p.direct) || !is_finite(p.indirect)) {
          ++counters.nonfinite_samples;
          return;
        }
        PathSample& sum = sums[size_t(pixel)];
        sum.direct += p.direct;
        sum.indirect += p.indirect;
        sum.albedo += p.albedo;
        sum.normal += p.normal;
        sum.depth += p.depth;
      });
      for (int pixel = 0; pixel < tile.pixels(); ++pixel)
        write_path_means(sums[size_t(pixel)], inv_spp, tile.x0 + pixel % tile.width(), tile.y0 + pixel / tile.width(),
                         frame);
    });
  });
  return frame;
}

}  // namespace sst
