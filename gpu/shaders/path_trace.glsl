// The GLSL twin of core/pt/path_tracer.cpp's trace_path and sample_direct: one camera path
// with next-event estimation and MIS (power heuristic) between light and BRDF sampling, in the
// C++'s order of operations and of random numbers, so that a path draws the CPU's samples and
// (up to the GPU's sqrt, division and trigonometry) computes the CPU's values.
//
// The including shader declares, before including this file:
//   the scene buffers (SCENE_BUFFERS(first), core/scene/scene_layout.h),
//   the light buffers (LIGHT_BUFFERS(first), core/lights/light_layout.h),
//   BVH_NODE / BVH_TRIANGLE and includes core/accel/bvh_traverse.h,
//   SCENE_RAY_EPSILON (EmbreeAccel's scene_ray_epsilon, for core/accel/ray_offset.h).
// Rays are traced through the flat BVH (bvh_traverse.h) where the CPU uses Embree: a ray that
// grazes an edge may hit on one backend and miss on the other (rare; see
// tests/gpu/path_trace_pass_test.cpp). A BVH stack overflow (never seen: the builder bounds the
// depth) counts as a miss for a path ray and as occluded for a shadow ray.
#ifndef SST_GPU_SHADERS_PATH_TRACE_GLSL
#define SST_GPU_SHADERS_PATH_TRACE_GLSL
#include "core/math/vector_math.h"
#include "core/material/brdf.h"
#include "gpu/shaders/light_sampler.glsl"
#include "core/accel/ray_offset.h"
#include "core/rng/sobol_sampler.h"
#include "gpu/shaders/surface.glsl"

// sst::PathSample: one camera path's contribution, split the way the EXR layers are.
struct PathSample {
  vec3 direct;    // emission seen + direct light at the first hit
  vec3 indirect;  // everything after the first bounce
  vec3 albedo;    // base colour at the first hit
  vec3 normal;    // shading normal at the first hit
  float depth;    // distance to the first hit; 0 for a miss
};

// The rays a path traced (sst::RayCounters' ray counts).
struct PathCounters {
  uint primary_rays;
  uint shadow_rays;
  uint bounce_rays;
};

PathCounters path_counters() { return PathCounters(0u, 0u, 0u); }

// Whether anything lies on the segment origin + t dir, t in [0, tmax).
bool path_occluded(vec3 origin, vec3 dir, float tmax) { return bvh_occluded(origin, dir, 0.0, tmax) != BVH_VISIBLE; }

// The closest hit along origin + t dir; false for a miss.
bool path_intersect(vec3 origin, vec3 dir, out BvhHit hit) {
  hit = bvh_intersect(origin, dir, 0.0, kInf);
  return hit.triangle < BVH_STACK_OVERFLOW;
}

// Next-event estimation at surface s: one light sample, one shadow ray, MIS-weighted.
vec3 sample_direct(Surface s, Brdf brdf, Basis basis, vec3 wo, vec2 u, inout PathCounters counters) {
  LightSample ls;
  if (!light_sample(s.p, u, ls)) return vec3(0.0);
  // Light from behind the geometric surface would leak through it: nothing is transmitted.
  if (dot3(ls.wi, s.ng) <= 0.0) return vec3(0.0);
  vec3 wi = to_local(basis, ls.wi);
  vec3 f = brdf_eval(brdf, wo, wi);
  if (wi.z <= 0.0 || max_component(f) <= 0.0 || max_component(ls.li) <= 0.0) return vec3(0.0);
  vec3 origin, dir;
  float tmax;
  if (isinf(ls.distance)) {
    origin = offset_ray_origin(SCENE_RAY_EPSILON, s.p, s.ng);
    dir = ls.wi;
    tmax = kInf;
  } else {
    shadow_ray_segment(SCENE_RAY_EPSILON, s.p, s.ng, ls.point, ls.normal, origin, dir, tmax);
  }
  ++counters.shadow_rays;
  if (path_occluded(origin, dir, tmax)) return vec3(0.0);
  float weight = ls.delta ? 1.0 : power_heuristic(ls.pdf, brdf_pdf(brdf, wo, wi));
  precise vec3 r = f * wi.z * ls.li * (weight / ls.pdf);
  return r;
}

// What first_hit holds after a miss (sst::Surface's defaults).
Surface path_no_surface() {
  Surface s;
  s.p = vec3(0.0);
  s.ng = vec3(0.0);
  s.ns = vec3(0.0);
  s.uv = vec2(0.0);
  s.triangle = 0u;
  s.material = 0u;
  s.front_face = true;
  s.base_color = vec3(1.0);
  s.metallic = 0.0;
  s.roughness = 1.0;
  s.emission = vec3(0.0);
  return s;
}

// trace_path: the camera ray origin + t dir, then up to max_bounces indirect bounces (0: direct
// light only), Russian roulette after rr_min_bounces. `first_hit` receives the surface the camera
// ray hit when `hit` is true (the many-light shaders shade it themselves after taking the direct
// light from here with max_bounces = 0, as core/manylight/many_light_method.cpp does).
PathSample trace_path(vec3 origin, vec3 dir, int max_bounces, int rr_min_bounces, bool diffuse_only,
                      inout PixelSampler ps, inout PathCounters counters, out Surface first_hit, out bool hit) {
  PathSample result;
  result.direct = vec3(0.0);
  result.indirect = vec3(0.0);
  result.albedo = vec3(0.0);
  result.normal = vec3(0.0);
  result.depth = 0.0;
  hit = false;
  ++counters.primary_rays;
  BvhHit h;
  if (!path_intersect(origin, dir, h)) {
    first_hit = path_no_surface();  // defined, never read: hit is false
    return result;
  }
  Surface s = make_surface(h.triangle, vec2(h.u, h.v), dir);
  first_hit = s;
  hit = true;
  result.albedo = s.base_color;
  result.normal = s.ns;
  precise float depth = h.t * length3(dir);
  result.depth = depth;
  result.direct = s.emission;

  vec3 beta = vec3(1.0);
  // Vertex k = 1 is the first hit. Light arriving at vertex k has made k-1 indirect bounces, so
  // vertices 1 .. max_bounces+1 gather light, and vertex 1's share is the direct layer.
  for (int k = 1; k <= max_bounces + 1; ++k) {
    Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, diffuse_only);
    Basis basis = basis_from_normal(s.ns);
    vec3 wo = to_local(basis, -normalize3(dir));
    if (wo.z <= 0.0) break;  // grazing view under the shading normal: no reflection defined

    // Every vertex draws its samples in the same order (light, BRDF, roulette), as on the CPU.
    vec2 u_light = pixel_sampler_get2d(ps), u_brdf = pixel_sampler_get2d(ps);
    float u_roulette = pixel_sampler_get1d(ps);
    precise vec3 direct = beta * sample_direct(s, brdf, basis, wo, u_light, counters);
    if (k == 1) result.direct += direct;
    else result.indirect += direct;

    BrdfSample bs;
    if (!brdf_sample(brdf, wo, u_brdf, bs)) break;
    vec3 wi = to_world(basis, bs.wi);
    if (dot3(wi, s.ng) <= 0.0) break;  // would pass through the surface

    origin = offset_ray_origin(SCENE_RAY_EPSILON, s.p, s.ng);
    dir = wi;
    ++counters.bounce_rays;
    BvhHit next;
    if (!path_intersect(origin, dir, next)) break;  // black world
    precise vec3 beta_next = beta * bs.weight;
    Surface ns = make_surface(next.triangle, vec2(next.u, next.v), dir);
    if (max_component(ns.emission) > 0.0) {
      float light_pdf = light_pdf_emissive_hit(s.p, next.triangle, ns.p, ns.ng);
      precise vec3 emitted = beta_next * ns.emission * power_heuristic(bs.pdf, light_pdf);
      if (k == 1) result.direct += emitted;
      else result.indirect += emitted;
    }
    beta = beta_next;
    s = ns;

    // Russian roulette after rr_min_bounces indirect bounces; k-1 have been made to reach s.
    if (k >= rr_min_bounces + 1 && k <= max_bounces) {
      float survive = min(1.0, max_component(beta));
      if (u_roulette >= survive) break;
      precise vec3 b = beta / survive;
      beta = b;
    }
  }
  return result;
}

#endif  // SST_GPU_SHADERS_PATH_TRACE_GLSL
