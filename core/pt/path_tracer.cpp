#include "core/pt/path_tracer.h"

#include "core/render/pixel_loop.h"
#include "core/shading/surface.h"
#include "core/sampling/sampling.h"

namespace sst {
namespace {

// Next-event estimation at surface s: one light sample, one shadow ray, MIS-weighted.
vec3 sample_direct(const RenderContext& ctx, const Surface& s, const Brdf& brdf, const Basis& basis, vec3 wo,
                   vec2 u, RayCounters& counters) {
  LightSample ls;
  if (!ctx.lights.sample(s.p, u, ls)) return vec3(0.0f);
  // Light from behind the geometric surface would leak through it: nothing is transmitted.
  if (glm::dot(ls.wi, s.ng) <= 0.0f) return vec3(0.0f);
  vec3 wi = to_local(basis, ls.wi);
  vec3 f = brdf_eval(brdf, wo, wi);
  if (wi.z <= 0.0f || max_component(f) <= 0.0f || max_component(ls.li) <= 0.0f) return vec3(0.0f);
  Ray shadow;
  if (std::isinf(ls.distance)) {
    shadow.origin = ctx.accel.offset_point(s.p, s.ng);
    shadow.direction = ls.wi;
  } else {
    shadow = ctx.accel.shadow_ray(s.p, s.ng, ls.point, ls.normal);
  }
  ++counters.shadow_rays;
  if (ctx.accel.occluded(shadow)) return vec3(0.0f);
  float weight = ls.delta ? 1.0f : power_heuristic(ls.pdf, brdf_pdf(brdf, wo, wi));
  return f * wi.z * ls.li * (weight / ls.pdf);
}

}  // namespace

PathSample trace_path(const RenderContext& ctx, const PathTracerParams& params, Ray ray, PixelSampler& sampler,
                      RayCounters& counters, Surface* first_hit) {
  PathSample out;
  ++counters.primary_rays;
  Hit hit = ctx.accel.intersect(ray);
  if (!hit.valid()) return out;
  Surface s = make_surface(ctx.scene, hit, ray.direction);
  if (first_hit) *first_hit = s;
  out.albedo = s.base_color;
  out.normal = s.ns;
  out.depth = hit.t * glm::length(ray.direction);
  out.direct = s.emission;

  vec3 beta(1.0f);
  // Vertex k = 1 is the first hit. Light arriving at vertex k has made k-1 indirect bounces, so
  // vertices 1 .. max_bounces+1 gather light, and vertex 1's share is the direct layer.
  for (int k = 1; k <= params.max_bounces + 1; ++k) {
    vec3& target = k == 1 ? out.direct : out.indirect;
    Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, ctx.options.diffuse_only);
    Basis basis = basis_from_normal(s.ns);
    vec3 wo = to_local(basis, -glm::normalize(ray.direction));
    if (wo.z <= 0.0f) break;  // grazing view under the shading normal: no reflection defined

    // Every vertex draws its samples in the same order (light, BRDF, roulette), so sample set
    // numbers line up across paths and the sets stay stratified per vertex.
    vec2 u_light = pixel_sampler_get2d(sampler), u_brdf = pixel_sampler_get2d(sampler);
    float u_roulette = pixel_sampler_get1d(sampler);
    target += beta * sample_direct(ctx, s, brdf, basis, wo, u_light, counters);

    BrdfSample bs;
    if (!brdf_sample(brdf, wo, u_brdf, bs)) break;
    vec3 wi = to_world(basis, bs.wi);
    if (glm::dot(wi, s.ng) <= 0.0f) break;  // would pass through the surface

    ray.origin = ctx.accel.offset_point(s.p, s.ng);
    ray.direction = wi;
    ray.tmin = 0.0f;
    ray.tmax = kInf;
    ++counters.bounce_rays;
    Hit next = ctx.accel.intersect(ray);
    if (!next.valid()) break;  // black world
    vec3 beta_next = beta * bs.weight;
    Surface ns = make_surface(ctx.scene, next, ray.direction);
    if (max_component(ns.emission) > 0.0f) {
      float light_pdf = ctx.lights.pdf_emissive_hit(s.p, next.triangle, ns.p, ns.ng);
      target += beta_next * ns.emission * power_heuristic(bs.pdf, light_pdf);
    }
    beta = beta_next;
    s = ns;

    // Russian roulette after rr_min_bounces indirect bounces; k-1 have been made to reach s.
    if (k >= params.rr_min_bounces + 1 && k <= params.max_bounces) {
      float survive = std::min(1.0f, max_component(beta));
      if (u_roulette >= survive) break;
      beta /= survive;
    }
  }
  return out;
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
  const int spp = ctx.options.spp;
  const float inv_spp = 1.0f / float(spp);
  timer.time("render", [&] {
    for_each_pixel(ctx.width, ctx.height, ctx.quiet, "pt", frame.counters, [&](int x, int y, RayCounters& counters) {
      uint32_t pixel = uint32_t(y) * uint32_t(ctx.width) + uint32_t(x);
      PathSample sum;
      for (int i = 0; i < spp; ++i) {
        PixelSampler sampler = pixel_sampler(ctx.options.seed, pixel, uint32_t(i));
        vec2 jitter = pixel_sampler_get2d(sampler);
        PathSample p = trace_path(ctx, params_, ctx.camera.generate(float(x) + jitter.x, float(y) + jitter.y), sampler, counters);
        ++counters.samples;
        // A NaN or Inf sample is a bug to find, not a pixel to show: drop and count it.
        if (!is_finite(p.direct) || !is_finite(p.indirect)) {
          ++counters.nonfinite_samples;
          continue;
        }
        sum.direct += p.direct;
        sum.indirect += p.indirect;
        sum.albedo += p.albedo;
        sum.normal += p.normal;
        sum.depth += p.depth;
      }
      frame.direct.set_rgb(x, y, sum.direct * inv_spp);
      frame.indirect.set_rgb(x, y, sum.indirect * inv_spp);
      frame.color.set_rgb(x, y, (sum.direct + sum.indirect) * inv_spp);
      frame.albedo.set_rgb(x, y, sum.albedo * inv_spp);
      vec3 n = sum.normal;
      frame.normal.set_rgb(x, y, glm::length(n) > 0.0f ? glm::normalize(n) : n);
      frame.depth.at(x, y, 0) = sum.depth * inv_spp;
    });
  });
  return frame;
}

}  // namespace sst
