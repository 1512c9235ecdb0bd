// One light path of instant radiosity (docs/design/methods.md; shared C++/GLSL source,
// vpl_generator.h is the generation): a light picked in proportion to its power, a point and a
// direction on it, then a VPL at every diffuse surface the path reaches, continued by
// cosine-weighted bounces with Russian roulette on the albedo after min_bounces. The path is a pure
// function of (seed, path) through HashRng(seed, path, 0, kVplStream), with its draws in a fixed
// order: pick, position (2), direction (2), then per hit the bounce direction (2) and roulette (1).
// A bounce from outside the view's surroundings aims part of its directions at them
// (light_path_bounce).
//
// Hooks, besides the scene's, the lights' and the ray queries (core/pt/trace_path.h lists those):
//   VPL_CTX_PARAM / VPL_CTX       where the VPLs go
//   VPL_DEPOSIT(deposit, hit, position, normal, intensity)
//                                 stores the path's deposit-th VPL, made at its hit-th surface hit
//                                 (0: the first), intensity not yet divided by the path count
#ifndef SST_CORE_VPL_LIGHT_PATH_H
#define SST_CORE_VPL_LIGHT_PATH_H
#include "core/accel/bvh_layout.h"
#include "core/accel/ray_offset.h"
#include "core/rng/hash_rng.h"
#include "core/sampling/sampling.h"
#include "core/vpl/light_path_bounce.h"
#include "core/vpl/light_path_layout.h"
#include "core/vpl/vpl_albedo.h"

#if !defined(VPL_CTX_PARAM) || !defined(VPL_CTX) || !defined(VPL_DEPOSIT)
#error "define the VPL_* hooks before including core/vpl/light_path.h"
#endif

SST_BEGIN

// Two draws as one 2D sample, the first draw in y: the order the VPL sets of the results were
// drawn in (once `vec2(next, next)`, which GCC evaluates right to left).
SST_FUNC vec2 light_path_next_2d(SST_INOUT(HashRng) rng) {
  float y = hash_rng_next(rng);
  float x = hash_rng_next(rng);
  return vec2(x, y);
}

// Light path `path` (directional lights aiming at `focus`, bounces from outside it too with share
// `focus_bounces`): its VPLs through VPL_DEPOSIT; returns (deposits, rays traced), deposits
// kLightPathOverflow where a traversal gave up.
SST_FUNC uvec2 trace_light_path(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM VPL_CTX_PARAM uint seed, uint path,
                                int max_bounces, int min_bounces, bool diffuse_only, SST_IN(EmissionFocus) focus,
                                float focus_bounces) {
  HashRng rng = hash_rng(seed, path, 0u, kVplStream);
  float u_pick = hash_rng_next(rng);
  vec2 u_pos = light_path_next_2d(rng);
  vec2 u_dir = light_path_next_2d(rng);
  EmissionSample e;
  if (!light_sample_emission(SCENE_CTX LIGHT_CTX u_pick, u_pos, u_dir, focus, e)) return uvec2(0u, 0u);
  vec3 origin = e.normal == vec3(0.0f) ? e.position : offset_ray_origin(RAY_EPSILON, e.position, e.normal);
  vec3 dir = e.direction;
  vec3 beta = e.weight;
  uint deposits = 0u;
  uint rays = 0u;
  for (int hit_index = 0; hit_index < max_bounces; ++hit_index) {
    rays += 1u;
    BvhHit hit = RAY_INTERSECT(origin, dir);
    if (hit.triangle == BVH_STACK_OVERFLOW) return uvec2(kLightPathOverflow, rays);
    if (hit.triangle == BVH_INVALID_TRIANGLE) break;
    Surface s = make_surface(SCENE_CTX hit.triangle, vec2(hit.u, hit.v), dir);
    vec3 albedo = vpl_albedo(s, diffuse_only);
    // Light arriving under the shading hemisphere is not reflected: the path tracer's rule.
    if (!(dot3(dir, s.ns) < 0.0f) || !(max_component(albedo) > 0.0f)) break;
    SST_PRECISE vec3 intensity = beta * albedo * kInvPi;
    if (!is_finite3(intensity)) break;
    VPL_DEPOSIT(deposits, hit_index, s.p, s.ns, intensity);
    deposits += 1u;
    if (hit_index + 1 >= max_bounces) break;

    vec2 u_bounce = light_path_next_2d(rng);
    float u_roulette = hash_rng_next(rng);
    if (hit_index + 1 >= min_bounces) {
      float survive = min(1.0f, max_component(albedo));
      if (u_roulette >= survive) break;
      SST_PRECISE vec3 b = beta / survive;
      beta = b;
    }
    // f cos / pdf = albedo x factor (1 where the bounce is cosine-weighted).
    vec3 wi = vec3(0.0f);
    float factor = 0.0f;
    if (!light_path_bounce(s.p, s.ns, u_bounce, focus.center, focus.radius, focus_bounces, wi, factor)) break;
    if (!(dot3(wi, s.ng) > 0.0f)) break;  // would pass through the surface
    SST_PRECISE vec3 reflected = beta * (albedo * factor);
    beta = reflected;
    origin = offset_ray_origin(s.offset, s.p, s.ng);
    dir = wi;
  }
  return uvec2(deposits, rays);
}

SST_END

#endif  // SST_CORE_VPL_LIGHT_PATH_H
