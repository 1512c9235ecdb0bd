// Where secondary and shadow rays start and end (shared C++/GLSL source), after pbrt-v4's
// error-bounded ray offsets: a point is lifted along its geometric normal just past the
// floating-point error of its coordinates, and the lifted coordinates are rounded away from the
// surface, so that a ray leaving it cannot meet its own surface again and nothing thinner than
// that error is skipped. No length here comes from the scene's size.
//
// The error of a point of triangle (v0, v1, v2) (triangle_point_offset) is gamma(7) times its own
// magnitude plus the triangle's largest vertex magnitude, per axis: that bounds both the rounding
// of the point interpolated from the vertices (pbrt-v4's gamma(7) sum |b_i v_i|, in which every
// |b_i v_i| is at most the largest vertex's) and the error with which the next ray's traversal
// places the same triangle (its plane distance is computed from the vertices relative to the
// ray's origin, Embree's as the flat BVH's). A point known only by its coordinates (a VPL, a
// substitute light, a G-buffer or cache point) takes the scene's bound: the same expression with
// the largest coordinate of any vertex (scene_ray_epsilon, core/accel/embree_accel.h), which
// covers every triangle of the scene.
#ifndef SST_CORE_ACCEL_RAY_OFFSET_H
#define SST_CORE_ACCEL_RAY_OFFSET_H
#include "core/math/vector_math.h"

SST_BEGIN

// gamma(7) of pbrt-v4, 7 u / (1 - 7 u) with u = 2^-24 (the relative error bound of 7 rounded float
// operations), rounded up.
SST_CONSTANT float kGamma7 = 4.1723275e-7f;

// u = 2^-24, the unit roundoff of float.
SST_CONSTANT float kUnitRoundoff = 5.9604645e-8f;

// How far a point p of triangle (v0, v1, v2) must be lifted along the unit normal n.
SST_FUNC float triangle_point_offset(vec3 v0, vec3 v1, vec3 v2, vec3 p, vec3 n) {
  vec3 m = max3(abs(v0), max3(abs(v1), abs(v2)));
  SST_PRECISE vec3 e = kGamma7 * (abs(p) + m);
  // Embree keeps a triangle as a vertex, two edges and their cross product, all rounded to float:
  // for a sliver that normal is off by about u L^2 / |Ng| radians (L the longest edge, |Ng| twice
  // the area), which tilts the plane a ray from p meets by up to L times that. Measured
  // (tests/core/accel/ray_offset_test.cpp): without this term 1 ray in 1000 leaving the
  // breakfast room's surfaces met its own triangle again in Embree.
  SST_PRECISE vec3 e01 = v1 - v0;
  SST_PRECISE vec3 e12 = v2 - v1;
  SST_PRECISE vec3 e20 = v0 - v2;
  float l2 = max(dot3(e01, e01), max(dot3(e12, e12), dot3(e20, e20)));
  float twice_area = length3(cross3(e01, e20));
  float tilt = twice_area > 0.0f ? 8.0f * kUnitRoundoff * (l2 / twice_area) * sqrt(l2) : 0.0f;
  SST_PRECISE float r = dot3(abs(n), e) + tilt;
  return r;
}

// The float after x toward +inf (-inf for next_float_down); infinities and NaN stay. From zero
// the smallest normal float, not a denormal, which GPUs and Embree may flush back to zero.
SST_FUNC float next_float_up(float x) {
  if ((isinf(x) && x > 0.0f) || isnan(x)) return x;
  if (x == 0.0f) return 1.17549435e-38f;  // from -0 too
  if (x == -1.17549435e-38f) return 0.0f;
  uint bits = floatBitsToUint(x);
  bits = x > 0.0f ? bits + 1u : bits - 1u;
  return uintBitsToFloat(bits);
}
SST_FUNC float next_float_down(float x) { return -next_float_up(-x); }

// p lifted by `offset` toward the side n points to (n unit, or zero for no lift), each coordinate
// then rounded one float further along n, as pbrt-v4 does: the addition's own rounding could
// otherwise return part of the lift, and a point exactly on an axis-aligned plane (whose error
// bound is 0) must still leave it.
SST_FUNC vec3 offset_ray_origin(float offset, vec3 p, vec3 n) {
  SST_PRECISE vec3 d = n * offset;
  SST_PRECISE vec3 r = p + d;
  r.x = n.x > 0.0f ? next_float_up(r.x) : (n.x < 0.0f ? next_float_down(r.x) : r.x);
  r.y = n.y > 0.0f ? next_float_up(r.y) : (n.y < 0.0f ? next_float_down(r.y) : r.y);
  r.z = n.z > 0.0f ? next_float_up(r.z) : (n.z < 0.0f ? next_float_down(r.z) : r.z);
  return r;
}

// A shadow ray between surface point p (geometric normal ng_p, on the side of y, lift offset_p)
// and y (normal ng_y, lift offset_y; ng_y = 0 for a point light, which has no surface): origin +
// t dir for t in [0, tmax], tmax just short of 1. Both ends are lifted off their surfaces:
// offsetting only the origin and shortening tmax by a constant fails at grazing angles, where the
// lifted ray meets the light's own plane up to offset / cos(theta) early and reports the light as
// its own occluder.
SST_FUNC void shadow_ray_segment(float offset_p, vec3 p, vec3 ng_p, float offset_y, vec3 y, vec3 ng_y,
                                 SST_OUT(vec3) origin, SST_OUT(vec3) dir, SST_OUT(float) tmax) {
  origin = offset_ray_origin(offset_p, p, ng_p);
  SST_PRECISE vec3 py = p - y;
  vec3 target = dot3(ng_y, py) < 0.0f ? offset_ray_origin(offset_y, y, -ng_y) : offset_ray_origin(offset_y, y, ng_y);
  SST_PRECISE vec3 d = target - origin;
  dir = d;
  tmax = 1.0f - 1e-4f;
}

SST_END

#endif  // SST_CORE_ACCEL_RAY_OFFSET_H
