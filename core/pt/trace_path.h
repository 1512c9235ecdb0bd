// One camera path of `pt` traced to its end (shared C++/GLSL source; path_tracer.h is the method):
// the stages of core/pt/path_stages.h with each ray traced as the path asks for it. Every
// method's direct light is this path with max_bounces = 0 (but rtslc's with direct_light = cuts:
// max_bounces = -1 and its own estimate, core/manylight/rtslc/rtslc_direct.h).
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
#include "core/pt/path_stages.h"

#if !defined(RAY_CTX_PARAM) || !defined(RAY_CTX) || !defined(RAY_INTERSECT) || !defined(RAY_OCCLUDED) || \
    !defined(RAY_EPSILON)
#error "define the RAY_* hooks before including core/pt/trace_path.h"
#endif

SST_BEGIN

// Light sample ls seen from p (geometric normal ng, terminator lift `lift`, ray lift `offset`)
// through the BRDF, with one shadow ray (light_sample_unshadowed, core/pt/path_stages.h).
SST_FUNC vec3 shade_light_sample(RAY_CTX_PARAM vec3 p, vec3 ng, vec3 lift, float offset, SST_IN(Brdf) brdf,
                                 SST_IN(Basis) basis, vec3 wo, SST_IN(LightSample) ls, bool mis,
                                 SST_INOUT(PathCounters) counters) {
  ShadowRay ray;
  bool needs_ray;
  vec3 r = light_sample_unshadowed(p, ng, lift, offset, brdf, basis, wo, ls, mis, ray, needs_ray);
  if (!needs_ray) return vec3(0.0f);
  counters.shadow_rays += 1u;
  if (RAY_OCCLUDED(ray.origin, ray.dir, ray.tmax)) return vec3(0.0f);
  return r;
}

// The camera ray origin + t dir, then up to cfg.max_bounces indirect bounces, each ray traced as
// the path asks for it. `st` ends with the path's PathSample, counters, sampler and first hit.
SST_FUNC void trace_path_state(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_INOUT(PathState) st,
                               SST_IN(PathConfig) cfg) {
  // One closest-hit site for the camera ray and every bounce (path_hit): a shader inlines the
  // traversal and the surface evaluation once.
  while (true) {
    BvhHit h = RAY_INTERSECT(st.origin, st.dir);
    path_hit(SCENE_CTX LIGHT_CTX st, h, cfg);
    if ((st.flags & PATH_ACTIVE) == 0u) break;
    path_shade(SCENE_CTX LIGHT_CTX st, cfg);
    bool occluded = false;
    if ((st.flags & PATH_RAY_SHADOW) != 0u) occluded = RAY_OCCLUDED(st.shadow.origin, st.shadow.dir, st.shadow.tmax);
    path_shadow_result(st, occluded);
    if ((st.flags & PATH_RAY_BOUNCE) == 0u) break;
  }
}

// The camera ray origin + t dir, then the path `cfg` asks for (PathConfig). `first_hit` receives
// the surface the camera ray hit when `hit` is true: the many-light methods shade it with their
// own indirect estimate after taking the direct light from here (core/manylight/direct_pass.h),
// so direct light is computed one way for all.
SST_FUNC PathSample trace_path(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM vec3 origin, vec3 dir,
                               SST_IN(PathConfig) cfg, SST_INOUT(PixelSampler) ps,
                               SST_INOUT(PathCounters) counters, SST_OUT(Surface) first_hit, SST_OUT(bool) hit) {
  PathState st = path_begin(origin, dir, ps);
  trace_path_state(SCENE_CTX LIGHT_CTX RAY_CTX st, cfg);
  ps = st.ps;
  counters.primary_rays += st.counters.primary_rays;
  counters.shadow_rays += st.counters.shadow_rays;
  counters.bounce_rays += st.counters.bounce_rays;
  first_hit = st.first_hit;
  hit = st.hit;
  return st.result;
}

SST_END

#endif  // SST_CORE_PT_TRACE_PATH_H
