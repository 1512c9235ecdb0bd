// The GLSL twin of core/vpl/vpl_shading.h and of shade_vpl (core/manylight/exhaustive_sampler.h):
// the light one VPL sends to a shading point x without visibility,
//   f(x, wi, wo) * max(0, n_x . wi) * I * max(0, n_j . (-wi)) / max(d^2, c^2),
// and with it: the shadow ray (ray_offset.glsl's shadow_ray, traced by bvh_occluded) only when
// that contribution is non-zero, counted as the CPU counts it.
//
// The includer provides, before including this file: the flat BVH traversal
// (core/accel/bvh_traverse.h with BVH_NODE/BVH_TRIANGLE defined) and SCENE_RAY_EPSILON
// (see gpu/shaders/ray_offset.glsl).
#ifndef SST_GPU_SHADERS_VPL_SHADING_GLSL
#define SST_GPU_SHADERS_VPL_SHADING_GLSL
#include "gpu/shaders/brdf.glsl"
#include "gpu/shaders/math.glsl"
#include "gpu/shaders/ray_offset.glsl"

// sst::Vpl.
struct Vpl {
  vec3 position;
  vec3 normal;  // unit, on the side the light arrived from
  vec3 intensity;
};

struct VplGeometry {
  vec3 wi;     // unit, from x toward the VPL
  float term;  // max(0, n_x.wi) * max(0, n_j.(-wi)) / max(d^2, c^2)
};

// n_x gives the cosine at x; ng_x (geometric normal on the viewer's side) rejects light from
// behind the surface.
VplGeometry vpl_geometry(Vpl vpl, vec3 x, vec3 n_x, vec3 ng_x, float clamp_distance) {
  VplGeometry g;
  g.wi = vec3(0.0);
  g.term = 0.0;
  precise vec3 d = vpl.position - x;
  float d2 = glm_dot(d, d);
  if (!(d2 > 0.0) || !is_finite(d2)) return g;  // coincident: no direction, no light
  precise vec3 wi = d / sqrt(d2);
  g.wi = wi;
  float cos_x = glm_dot(n_x, g.wi), cos_j = -glm_dot(vpl.normal, g.wi);
  if (!(cos_x > 0.0) || !(cos_j > 0.0) || !(glm_dot(ng_x, g.wi) > 0.0)) return g;
  precise float c2 = clamp_distance * clamp_distance;
  precise float term = cos_x * cos_j / max(d2, c2);
  g.term = term;
  return g;
}

// Reflected radiance toward wo_local (in `frame`, frame.n = n_x) at a surface with `brdf`.
vec3 vpl_contribution(Vpl vpl, vec3 x, vec3 ng_x, Frame frame, Brdf brdf, vec3 wo_local, float clamp_distance) {
  VplGeometry g = vpl_geometry(vpl, x, frame.n, ng_x, clamp_distance);
  if (!(g.term > 0.0)) return vec3(0.0);
  vec3 f = brdf_eval(brdf, wo_local, frame_to_local(frame, g.wi));
  precise vec3 c = f * vpl.intensity * g.term;
  return c;
}

// The contribution with visibility; adds one to shadow_rays when a shadow ray is traced (only for
// a non-zero contribution). An overflowing BVH stack (never, for a built tree) counts as occluded.
vec3 shade_vpl(vec3 x, vec3 ng_x, Frame frame, Brdf brdf, vec3 wo_local, Vpl vpl, float clamp_distance,
               inout uint shadow_rays) {
  vec3 c = vpl_contribution(vpl, x, ng_x, frame, brdf, wo_local, clamp_distance);
  if (max_component(c) <= 0.0) return vec3(0.0);
  ++shadow_rays;
  vec3 origin, dir;
  float tmax;
  shadow_ray(x, ng_x, vpl.position, vpl.normal, origin, dir, tmax);
  if (bvh_occluded(origin, dir, 0.0, tmax) != BVH_VISIBLE) return vec3(0.0);
  return c;
}

#endif
