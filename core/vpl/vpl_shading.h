// The light one VPL sends to a shading point x (METHODS.md §1), without visibility:
//   f(x, wi, wo) * max(0, n_x . wi) * I * max(0, n_j . (-wi)) / max(d^2, c^2)
// wi = unit direction from x to the VPL, d = distance, c = the singularity clamp distance
// (vpl_clamp.h). The clamp bounds the 1/d^2 spike of a VPL right next to x, at the price of
// slightly darker corners (the papers say the same). Every sampler and the exhaustive method use
// these functions, so they all compute the same thing; visibility (vpl_shadow_ray) is separate
// because samplers trace it at different times. c should be > 0: with c = 0 a VPL at x gives 0
// (no direction) but one a hair away gives a huge value.
#pragma once
#include "core/accel/embree_accel.h"
#include "core/material/brdf.h"
#include "core/math/math.h"
#include "core/vpl/vpl.h"

namespace sst {

struct VplGeometry {
  vec3 wi{0.0f};       // unit, from x toward the VPL
  float term = 0.0f;   // max(0, n_x.wi) * max(0, n_j.(-wi)) / max(d^2, c^2)
};

// The geometric part. `n_x` gives the cosine at x; `ng_x` (the geometric normal on the viewer's
// side) rejects light from behind the surface, which would otherwise leak through it under a
// bent shading normal, exactly as the path tracer's light sampling does.
inline VplGeometry vpl_geometry(const Vpl& vpl, vec3 x, vec3 n_x, vec3 ng_x, float clamp_distance) {
  VplGeometry g;
  vec3 d = vpl.position - x;
  float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f) || !std::isfinite(d2)) return g;  // coincident: no direction, no light
  g.wi = d / std::sqrt(d2);
  float cos_x = glm::dot(n_x, g.wi), cos_j = -glm::dot(vpl.normal, g.wi);
  if (!(cos_x > 0.0f) || !(cos_j > 0.0f) || !(glm::dot(ng_x, g.wi) > 0.0f)) return g;
  g.term = cos_x * cos_j / std::max(d2, clamp_distance * clamp_distance);
  return g;
}

// Irradiance at x from the VPL (diffuse shading: radiance = albedo / pi * this).
inline vec3 vpl_irradiance(const Vpl& vpl, vec3 x, vec3 n_x, vec3 ng_x, float clamp_distance) {
  return vpl.intensity * vpl_geometry(vpl, x, n_x, ng_x, clamp_distance).term;
}

// Reflected radiance toward wo at a surface with BRDF `brdf` in shading frame `frame` (n_x =
// frame.n); wo_local is in that frame.
inline vec3 vpl_contribution(const Vpl& vpl, vec3 x, vec3 ng_x, const Frame& frame, const Brdf& brdf, vec3 wo_local,
                             float clamp_distance) {
  VplGeometry g = vpl_geometry(vpl, x, frame.n, ng_x, clamp_distance);
  if (!(g.term > 0.0f)) return vec3(0.0f);
  return brdf.eval(wo_local, frame.to_local(g.wi)) * vpl.intensity * g.term;
}

// The shadow ray between x (geometric normal ng_x, on the VPL's side) and the VPL, both ends
// lifted off their surfaces (EmbreeAccel::shadow_ray).
inline Ray vpl_shadow_ray(const EmbreeAccel& accel, vec3 x, vec3 ng_x, const Vpl& vpl) {
  return accel.shadow_ray(x, ng_x, vpl.position, vpl.normal);
}

}  // namespace sst
