// The light one VPL sends to a shading point x (docs/design/methods.md), without visibility:
//   f(x, wi, wo) * max(0, n_x . wi) * I * max(0, n_j . (-wi)) / max(d^2, c^2)
// wi = unit direction from x to the VPL, d = distance, c = the singularity clamp distance
// (vpl_clamp_at below). The clamp bounds the 1/d^2 spike of a VPL right next to x; what it removes
// is added back by the direct pass's compensating path (core/manylight/direct_pass.h) unless
// VplParams::clamp_compensation is off, as in the papers, whose corners the clamp darkens. Every
// sampler and the exhaustive method use these functions on both backends (shared C++/GLSL
// source), so they all compute the same thing; visibility is separate because samplers trace it
// at different times. c should be > 0: with c = 0 a VPL at x gives 0 (no direction) but one a
// hair away gives a huge value.
#ifndef SST_CORE_VPL_VPL_SHADING_H
#define SST_CORE_VPL_VPL_SHADING_H
#include "core/material/brdf.h"
#include "core/math/vector_math.h"
#include "core/vpl/vpl.h"

SST_BEGIN

// The clamp distance c at a point `depth` metres from the camera: a fixed part (the set's
// vpl_clamp_distance, 0 when the clamp follows the camera) or per_depth x depth, whichever is
// larger. Per depth, c subtends the same angle from the camera wherever the point lies, and
// nothing outside the view (a ground plane, a sky dome) changes it (docs/design/lengths.md).
SST_FUNC float vpl_clamp_at(float fixed_distance, float per_depth, float depth) {
  SST_PRECISE float c = per_depth * depth;
  return max(fixed_distance, c);
}

// What the clamp removes from the light a point y sends to x, as a share of it: 1 - d^2/c^2
// (1/d^2 against 1/max(d^2, c^2)), 0 at or beyond c.
SST_FUNC float vpl_clamp_residual(vec3 x, vec3 y, float c) {
  SST_PRECISE vec3 d = y - x;
  SST_PRECISE float d2 = dot3(d, d);
  SST_PRECISE float c2 = c * c;
  SST_PRECISE float r = 1.0f - d2 / c2;
  return d2 < c2 ? r : 0.0f;
}

struct VplGeometry {
  vec3 wi SST_DEFAULT(vec3(0.0f));  // unit, from x toward the VPL
  float term SST_DEFAULT(0.0f);     // max(0, n_x.wi) * max(0, n_j.(-wi)) / max(d^2, c^2)
};

// The geometric part. `n_x` gives the cosine at x; `ng_x` (the geometric normal on the viewer's
// side) rejects light from behind the surface, which would otherwise leak through it under a
// bent shading normal, exactly as the path tracer's light sampling does.
SST_FUNC VplGeometry vpl_geometry(SST_IN(Vpl) vpl, vec3 x, vec3 n_x, vec3 ng_x, float clamp_distance) {
  VplGeometry g;
  g.wi = vec3(0.0f);
  g.term = 0.0f;
  SST_PRECISE vec3 d = vpl.position - x;
  float d2 = dot3(d, d);
  if (!(d2 > 0.0f) || !is_finite(d2)) return g;  // coincident: no direction, no light
  SST_PRECISE vec3 wi = d / sqrt(d2);
  g.wi = wi;
  float cos_x = dot3(n_x, g.wi);
  float cos_j = -dot3(vpl.normal, g.wi);
  if (!(cos_x > 0.0f) || !(cos_j > 0.0f) || !(dot3(ng_x, g.wi) > 0.0f)) return g;
  SST_PRECISE float c2 = clamp_distance * clamp_distance;
  SST_PRECISE float term = cos_x * cos_j / max(d2, c2);
  g.term = term;
  return g;
}

// Irradiance at x from the VPL (diffuse shading: radiance = albedo / pi * this).
SST_FUNC vec3 vpl_irradiance(SST_IN(Vpl) vpl, vec3 x, vec3 n_x, vec3 ng_x, float clamp_distance) {
  SST_PRECISE vec3 e = vpl.intensity * vpl_geometry(vpl, x, n_x, ng_x, clamp_distance).term;
  return e;
}

// Reflected radiance toward wo at a surface with BRDF `brdf` in shading basis `basis` (n_x =
// basis.n); wo_local is in that basis.
SST_FUNC vec3 vpl_contribution(SST_IN(Vpl) vpl, vec3 x, vec3 ng_x, SST_IN(Basis) basis, SST_IN(Brdf) brdf,
                               vec3 wo_local, float clamp_distance) {
  VplGeometry g = vpl_geometry(vpl, x, basis.n, ng_x, clamp_distance);
  if (!(g.term > 0.0f)) return vec3(0.0f);
  vec3 f = brdf_eval(brdf, wo_local, to_local(basis, g.wi));
  SST_PRECISE vec3 c = f * vpl.intensity * g.term;
  return c;
}

SST_END

#ifdef __cplusplus
#include "core/accel/embree_accel.h"
namespace sst {
// The shadow ray between x (geometric normal ng_x, on the VPL's side) and the VPL, both ends
// lifted off their surfaces (EmbreeAccel::shadow_ray).
inline Ray vpl_shadow_ray(const EmbreeAccel& accel, vec3 x, vec3 ng_x, const Vpl& vpl) {
  return accel.shadow_ray(x, ng_x, vpl.position, vpl.normal);
}
}  // namespace sst
#endif

#endif  // SST_CORE_VPL_VPL_SHADING_H
