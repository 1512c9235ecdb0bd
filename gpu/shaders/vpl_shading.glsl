// shade_vpl (core/manylight/exhaustive_sampler.h) on the GPU: core/vpl/vpl_shading.h's
// contribution with visibility: the shadow ray (ray_offset.glsl's shadow_ray, traced by bvh_occluded) only when
// that contribution is non-zero, counted as the CPU counts it.
//
// The includer provides, before including this file: the flat BVH traversal
// (core/accel/bvh_traverse.h with BVH_NODE/BVH_TRIANGLE defined) and SCENE_RAY_EPSILON
// (see gpu/shaders/ray_offset.glsl).
#ifndef SST_GPU_SHADERS_VPL_SHADING_GLSL
#define SST_GPU_SHADERS_VPL_SHADING_GLSL
#include "core/vpl/vpl_shading.h"
#include "gpu/shaders/ray_offset.glsl"

// The contribution with visibility; adds one to shadow_rays when a shadow ray is traced (only for
// a non-zero contribution). An overflowing BVH stack (never, for a built tree) counts as occluded.
vec3 shade_vpl(vec3 x, vec3 ng_x, Basis basis, Brdf brdf, vec3 wo_local, Vpl vpl, float clamp_distance,
               inout uint shadow_rays) {
  vec3 c = vpl_contribution(vpl, x, ng_x, basis, brdf, wo_local, clamp_distance);
  if (max_component(c) <= 0.0) return vec3(0.0);
  ++shadow_rays;
  vec3 origin, dir;
  float tmax;
  shadow_ray(x, ng_x, vpl.position, vpl.normal, origin, dir, tmax);
  if (bvh_occluded(origin, dir, 0.0, tmax) != BVH_VISIBLE) return vec3(0.0);
  return c;
}

#endif
