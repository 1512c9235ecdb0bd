// One camera path of `pt` (shared C++/GLSL source; path_tracer.h is the method): next-event
// estimation with MIS (power heuristic) between light and BRDF sampling at every vertex, Russian
// roulette after rr_min_bounces. Every method's direct light is this path with max_bounces = 0 (but
// rtslc's with direct_light = cuts: max_bounces = -1 and its own estimate, core/manylight/rtslc/rtslc_direct.h).
//
// Hooks, besides the scene's (core/shading/surface_eval.h) and the lights' (core/lights/
// light_sample.h), which the includer has bound already: the ray queries
//   RAY_CTX_PARAM / RAY_CTX       the context parameter and argument (empty in GLSL)
//   RAY_INTERSECT(origin, dir)    BvhHit: the closest hit along origin + t dir, t in [0, inf);
//                                 triangle BVH_INVALID_TRIANGLE for a miss, BVH_STACK_OVERFLOW
//                                 where a traversal gave up (counted as a miss)
//   RAY_OCCLUDED(origin, dir, tmax)  bool: anything on origin + t dir, t in [0, tmax)
//   RAY_EPSILON                   the ray offset of a point known only by its coordinates
//                                 (scene_ray_epsilon, core/accel/ray_offset.h)
// The CPU binds them to EmbreeAccel (core/accel/embree_accel.h), the GPU to the flat BVH
// (gpu/shaders/path_trace.glsl).
#ifndef SST_CORE_PT_TRACE_PATH_H
#define SST_CORE_PT_TRACE_PATH_H
#include "core/accel/bvh_layout.h"
#include "core/accel/ray_offset.h"
#include "core/material/brdf.h"
#include "core/rng/sobol_sampler.h"
#include "core/sampling/sampling.h"

#if !defined(RAY_CTX_PARAM) || !defined(RAY_CTX) || !defined(RAY_INTERSECT) || !defined(RAY_OCCLUDED) || \
    !defined(RAY_EPSILON)
#error "define the RAY_* hooks before including core/pt/trace_path.h"
#endif

SST_BEGIN

// One camera path's contribution, split the way the EXR layers are.
struct PathSample {
  vec3 direct SST_DEFAULT(vec3(0.0f));    // emission seen + direct light at the first hit
  vec3 indirect SST_DEFAULT(vec3(0.0f));  // everything after the first bounce
  vec3 albedo SST_DEFAULT(vec3(0.0f));    // base colour at the first hit
  vec3 normal SST_DEFAULT(vec3(0.0f));    // shading normal at the first hit
  float depth SST_DEFAULT(0.0f);          // distance to the first hit; 0 for a miss
};

// The rays a path traced.
struct PathCounters {
  uint primary_rays SST_DEFAULT(0u);
  uint shadow_rays SST_DEFAULT(0u);
  uint bounce_rays SST_DEFAULT(0u);
};

SST_FUNC PathCounters path_counters() {
  PathCounters c;
  c.primary_rays = 0u;
  c.shadow_rays = 0u;
  c.bounce_rays = 0u;
  return c;
}

// Light sample ls seen from p (geometric normal ng, ray lift `offset`) through the BRDF, with one
// shadow ray: weighted by the power heuristic against BRDF sampling when `mis`, else the only
// estimate of that light's contribution.
SST_FUNC vec3 shade_light_sample(RAY_CTX_PARAM vec3 p, vec3 ng, float offset, SST_IN(Brdf) brdf, SST_IN(Basis) basis,
                                 vec3 wo, SST_IN(LightSample) ls, bool mis, SST_INOUT(PathCounters) counters) {
  // Light from behind the geometric surface would leak through it: nothing is transmitted.
  if (dot3(ls.wi, ng) <= 0.0f) return vec3(0.0f);
  vec3 wi = to_local(basis, ls.wi);
  vec3 f = brdf_eval(brdf, wo, wi);
  if (wi.z <= 0.0f || max_component(f) <= 0.0f || max_component(ls.li) <= 0.0f) return vec3(0.0f);
  vec3 origin;
  vec3 dir;
  float tmax;
  if (isinf(ls.distance)) {
    origin = offset_ray_origin(offset, p, ng);
    dir = ls.wi;
    tmax = kInf;
  } else {
    shadow_ray_segment(offset, p, ng, ls.offset, ls.point, ls.normal, origin, dir, tmax);
  }
  counters.shadow_rays += 1u;
  if (RAY_OCCLUDED(origin, dir, tmax)) return vec3(0.0f);
  float weight = ls.delta || !mis ? 1.0f : power_heuristic(ls.pdf, brdf_pdf(brdf, wo, wi));
  SST_PRECISE vec3 r = f * wi.z * ls.li * (weight / ls.pdf);
  return r;
}

// Next-event estimation at surface s: one light sample, one shadow ray, MIS-weighted.
SST_FUNC vec3 sample_direct(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(Surface) s, SST_IN(Brdf) brdf,
                            SST_IN(Basis) basis, vec3 wo, vec2 u, SST_INOUT(PathCounters) counters) {
  LightSample ls;
  if (!light_sample(SCENE_CTX LIGHT_CTX s.p, s.ns, u, ls)) return vec3(0.0f);
  return shade_light_sample(RAY_CTX s.p, s.ng, s.offset, brdf, basis, wo, ls, true, counters);
}

// a * b, never contracted into the addition it feeds. A helper rather than precise variables in
// trace_path: glslang traces a precise variable back through every call argument and
// loop-carried value that feeds it, which in trace_path's loop took it minutes and gigabytes
// (and whether it did changed with unrelated edits); here the trace ends at the parameters.
SST_FUNC vec3 product_exact(vec3 a, vec3 b) {
  SST_PRECISE vec3 r = a * b;
  return r;
}

// What first_hit holds after a miss: Surface's defaults.
SST_FUNC Surface surface_none() {
  Surface s;
  s.p = vec3(0.0f);
  s.ng = vec3(0.0f);
  s.ns = vec3(0.0f);
  s.uv = vec2(0.0f);
  s.triangle = 0u;
  s.material = 0u;
  s.front_face = true;
  s.base_color = vec3(1.0f);
  s.metallic = 0.0f;
  s.roughness = 1.0f;
  s.emission = vec3(0.0f);
  s.offset = 0.0f;
  return s;
}

// The camera ray origin + t dir, then up to max_bounces indirect bounces (0: direct light only;
// -1: the first hit and its emission only, for a method that samples the direct light itself),
// Russian roulette after rr_min_bounces. `first_hit` receives the surface the camera ray hit when
// `hit` is true: the many-light methods shade it with their own indirect estimate after taking
// the direct light from here (max_bounces = 0), so direct light is computed one way for all.
SST_FUNC PathSample trace_path(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM vec3 origin, vec3 dir, int max_bounces,
                               int rr_min_bounces, bool diffuse_only, SST_INOUT(PixelSampler) ps,
                               SST_INOUT(PathCounters) counters, SST_OUT(Surface) first_hit, SST_OUT(bool) hit) {
  PathSample result;
  result.direct = vec3(0.0f);
  result.indirect = vec3(0.0f);
  result.albedo = vec3(0.0f);
  result.normal = vec3(0.0f);
  result.depth = 0.0f;
  hit = false;
  first_hit = surface_none();
  counters.primary_rays += 1u;
  BvhHit h = RAY_INTERSECT(origin, dir);
  if (h.triangle >= BVH_STACK_OVERFLOW) return result;
  Surface s = make_surface(SCENE_CTX h.triangle, vec2(h.u, h.v), dir);
  first_hit = s;
  hit = true;
  result.albedo = s.base_color;
  result.normal = s.ns;
  result.depth = h.t * length3(dir);
  result.direct = s.emission;

  vec3 beta = vec3(1.0f);
  // Vertex k = 1 is the first hit. Light arriving at vertex k has made k-1 indirect bounces, so
  // vertices 1 .. max_bounces+1 gather light, and vertex 1's share is the direct layer.
  for (int k = 1; k <= max_bounces + 1; ++k) {
    Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, diffuse_only);
    // A view under the interpolated normal but above the facet (a coarse curved mesh seen at a
    // grazing angle) is shaded with the facet's normal: ending the path there lost the light such
    // surfaces reflect, darkening what they light (results/README.md, thin tubes against Cycles).
    Basis basis = basis_from_normal(s.ns);
    vec3 wo = to_local(basis, -normalize3(dir));
    if (wo.z <= 0.0f) {
      basis = basis_from_normal(s.ng);
      wo = to_local(basis, -normalize3(dir));
    }
    if (wo.z <= 0.0f) break;  // exactly grazing the facet: no reflection defined

    // Every vertex draws its samples in the same order (light, BRDF, roulette), so sample set
    // numbers line up across paths and the sets stay stratified per vertex.
    vec2 u_light = pixel_sampler_get2d(ps);
    vec2 u_brdf = pixel_sampler_get2d(ps);
    float u_roulette = pixel_sampler_get1d(ps);
    vec3 direct = product_exact(beta, sample_direct(SCENE_CTX LIGHT_CTX RAY_CTX s, brdf, basis, wo, u_light, counters));
    if (k == 1) result.direct += direct;
    else result.indirect += direct;
    // The last vertex's bounce ray only looks for emission (the MIS half of its direct light): in a
    // scene where no triangle emits (LightHeader.emissive_count) it would find none. It cost the
    // many-light methods' direct pass (max_bounces 0) a third of its rays.
    if (k == max_bounces + 1 && LIGHT_HEADER.emissive_count == 0u) break;

    BrdfSample bs;
    if (!brdf_sample(brdf, wo, u_brdf, bs)) break;
    vec3 wi = to_world(basis, bs.wi);
    if (dot3(wi, s.ng) <= 0.0f) break;  // would pass through the surface

    origin = offset_ray_origin(s.offset, s.p, s.ng);
    dir = wi;
    counters.bounce_rays += 1u;
    BvhHit next = RAY_INTERSECT(origin, dir);
    if (next.triangle >= BVH_STACK_OVERFLOW) break;  // black world
    vec3 beta_next = beta * bs.weight;
    Surface ns = make_surface(SCENE_CTX next.triangle, vec2(next.u, next.v), dir);
    if (max_component(ns.emission) > 0.0f) {
      float light_pdf = light_pdf_emissive_hit(SCENE_CTX LIGHT_CTX s.p, s.ns, next.triangle, ns.p, ns.ng);
      vec3 emitted = product_exact(beta_next * ns.emission, vec3(power_heuristic(bs.pdf, light_pdf)));
      if (k == 1) result.direct += emitted;
      else result.indirect += emitted;
    }
    beta = beta_next;
    s = ns;

    // Russian roulette after rr_min_bounces indirect bounces; k-1 have been made to reach s.
    // (k > rr_min_bounces, not k >= rr_min_bounces + 1, which overflows at INT_MAX.)
    if (k > rr_min_bounces && k <= max_bounces) {
      float survive = min(1.0f, max_component(beta));
      if (u_roulette >= survive) break;
      beta = beta / survive;
    }
  }
  return result;
}

SST_END

#endif  // SST_CORE_PT_TRACE_PATH_H
