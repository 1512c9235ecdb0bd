#include "core/manylight/many_light_method.h"

#include <atomic>
#include <mutex>

#include "core/manylight/shading_point.h"
#include "core/pt/path_tracer.h"
#include "core/render/pixel_loop.h"
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

ManyLightMethod::ManyLightMethod(VplParams vpl_params, nlohmann::json params, std::unique_ptr<IndirectSampler> sampler)
    : vpl_params_(vpl_params), params_(std::move(params)), sampler_(std::move(sampler)) {
  validate(vpl_params_);
}

FrameOutput ManyLightMethod::render(const RenderContext& ctx, StageTimer& timer) {
  FrameOutput frame;
  frame.allocate(ctx.width, ctx.height);
  Image variance(ctx.width, ctx.height), depth(ctx.width, ctx.height, 1);

  VplStats vpl_stats;
  VplSet vpls = timer.time("vpl_generation", [&] {
    return generate_vpls(ctx.scene, ctx.accel, ctx.lights, vpl_params_, ctx.options.seed, ctx.options.diffuse_only,
                         &vpl_stats);
  });
  if (!vpl_params_.export_vpls.empty()) write_vpls_ply(vpl_params_.export_vpls, vpls);
  VplLighting lighting{ctx, vpls, vpl_stats.clamp_distance};
  frame.method_counters["vpl"] = to_json(vpl_stats);
  sampler_->prepare(lighting, timer, frame.method_counters);

  PathTracerParams direct_only;
  const bool own_direct = sampler_->estimates_direct();
  direct_only.max_bounces = own_direct ? -1 : 0;
  Accumulators acc;
  const int spp = ctx.options.spp;
  timer.time("sampling", [&] {
    for_each_pixel(ctx.width, ctx.height, ctx.quiet, "sampling", frame.counters, [&](int x, int y, RayCounters& rc) {
      uint32_t pixel = uint32_t(y) * uint32_t(ctx.width) + uint32_t(x);
      vec3 direct(0.0f), indirect(0.0f), indirect2(0.0f), albedo(0.0f), normal(0.0f);
      float z = 0.0f;
      uint64_t nodes = 0, samples = 0;
      std::vector<uint32_t> depths;
      for (int i = 0; i < spp; ++i) {
        PixelSampler sampler = pixel_sampler(ctx.options.seed, pixel, uint32_t(i));
        vec2 jitter = pixel_sampler_get2d(sampler);
        Ray ray = ctx.camera.generate(float(x) + jitter.x, float(y) + jitter.y);
        Surface hit;
        PathSample d = trace_path(ctx, direct_only, ray, sampler, rc, &hit);
        ++rc.samples;
        vec3 value(0.0f);
        if (d.depth > 0.0f) {
          ShadingPoint sp = shading_point(hit, ray.direction, ctx.options.diffuse_only, x, y);
          if (own_direct) d.direct += sampler_->estimate_direct(ctx, sp, sampler, rc);
          IndirectEstimate e = sampler_->estimate(sp, sampler);
          rc.shadow_rays += e.shadow_rays;
          nodes += e.nodes_visited;
          ++samples;
          depths.push_back(e.nodes_visited);
          value = e.value;
        }
        if (!is_finite(d.direct) || !is_finite(value)) {
          ++rc.nonfinite_samples;
          continue;
        }
        direct += d.direct;
        indirect += value;
        indirect2 += value * value;
        albedo += d.albedo;
        normal += d.normal;
        z += d.depth;
      }
      float inv = 1.0f / float(spp);
      vec3 mean = indirect * inv;
      frame.direct.set_rgb(x, y, direct * inv);
      frame.indirect.set_rgb(x, y, mean);
      frame.color.set_rgb(x, y, (direct + indirect) * inv);
      frame.albedo.set_rgb(x, y, albedo * inv);
      frame.normal.set_rgb(x, y, glm::length(normal) > 0.0f ? glm::normalize(normal) : normal);
      frame.depth.at(x, y, 0) = z * inv;
      // Variance of the pixel mean (sample variance / spp), for per-pixel z-tests.
      vec3 var = spp > 1 ? glm::max(indirect2 * inv - mean * mean, vec3(0.0f)) / float(spp - 1) : vec3(0.0f);
      variance.set_rgb(x, y, var);
      depth.at(x, y, 0) = samples ? float(nodes) / float(samples) : 0.0f;
      acc.nodes += nodes;
      acc.indirect_samples += samples;
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
