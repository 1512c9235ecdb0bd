// Where a light path of instant radiosity goes from a surface (core/vpl/light_path.h; shared
// C++/GLSL source, without the path's hooks so that tests can draw bounces alone).
#ifndef SST_CORE_VPL_LIGHT_PATH_BOUNCE_H
#define SST_CORE_VPL_LIGHT_PATH_BOUNCE_H
#include "core/math/vector_math.h"
#include "core/sampling/sampling.h"

SST_BEGIN

// The direction a light path leaves a surface point p (shading normal ns) in, and the factor cos /
// (pi pdf) its throughput is multiplied by besides the albedo; false where the direction is under
// the surface. Inside the focus sphere (the view's surroundings: the EmissionFocus of
// core/lights/light_sample.h, its first disc's radius about the camera), or without one (radius 0),
// it is cosine-weighted (factor 1). Outside, a share `focus_bounces` of the directions is drawn
// uniformly in the cone the sphere subtends and the rest cosine-weighted, weighted by the mixture's
// pdf, so the path stays unbiased. A path from sunlit ground a kilometre away then reaches the room
// in view with a probability that does not fall as distance^-3, nor does its weight there grow as
// distance^2: without the cone, a rare path bounced into a window from afar is a VPL bright enough
// to move a frame's mean by tens of percent (docs/design/lengths.md).
SST_FUNC bool light_path_bounce(vec3 p, vec3 ns, vec2 u, vec3 focus_center, float focus_radius, float focus_bounces,
                                SST_INOUT(vec3) wi, SST_INOUT(float) factor) {
  SST_PRECISE vec3 to_center = focus_center - p;
  float d2 = dot3(to_center, to_center);
  SST_PRECISE float r2 = focus_radius * focus_radius;
  if (!(focus_bounces > 0.0f) || !(focus_radius > 0.0f) || !(d2 > r2)) {
    wi = to_world(basis_from_normal(ns), sample_cosine_hemisphere(u.x, u.y));
    factor = 1.0f;
    return true;
  }
  SST_PRECISE float sin2 = r2 / d2;
  SST_PRECISE float cos_max = sqrt(1.0f - sin2);
  SST_PRECISE float one_minus_cos = sin2 / (1.0f + cos_max);
  if (u.x < focus_bounces) {
    SST_PRECISE float u_cone = u.x / focus_bounces;
    wi = to_world(basis_from_normal(normalize3(to_center)), sample_uniform_cone(u_cone, u.y, one_minus_cos));
  } else {
    SST_PRECISE float u_cos = (u.x - focus_bounces) / (1.0f - focus_bounces);
    wi = to_world(basis_from_normal(ns), sample_cosine_hemisphere(u_cos, u.y));
  }
  float cos_n = dot3(wi, ns);
  if (!(cos_n > 0.0f)) return false;
  // In the cone: the ray passes within the radius of the centre.
  vec3 off_axis = cross3(wi, to_center);
  bool in_cone = dot3(wi, to_center) > 0.0f && dot3(off_axis, off_axis) <= r2;
  SST_PRECISE float pdf_cos = (1.0f - focus_bounces) * cos_n * kInvPi;
  SST_PRECISE float pdf_cone = focus_bounces / (2.0f * kPi * one_minus_cos);
  SST_PRECISE float pdf = pdf_cos + (in_cone ? pdf_cone : 0.0f);
  SST_PRECISE float f = cos_n * kInvPi / pdf;
  factor = f;
  return true;
}

SST_END

#endif  // SST_CORE_VPL_LIGHT_PATH_BOUNCE_H
