// Bounds of a light-tree node's box [lo, hi] as seen from a shading point x: what every tree
// sampler's weights are built from (SLC, SST, RTSLC, the hybrid's cuts over VPLs; the emitter
// tree's slc weights over the scene's lights), on both backends
// (shared C++/GLSL source). Decisions taken on these values (which child, whether a box is
// behind the surface) must be the same on the CPU and the GPU, hence the precise temporaries.
#ifndef SST_CORE_MATH_BOX_BOUNDS_H
#define SST_CORE_MATH_BOX_BOUNDS_H
#include "core/math/vector_math.h"

SST_BEGIN

// Squared distance from x to the box (0 inside; +inf for an empty box).
SST_FUNC float box_distance2_min(vec3 lo, vec3 hi, vec3 x) {
  if (box_empty(lo, hi)) return kInf;
  SST_PRECISE vec3 below = lo - x;
  SST_PRECISE vec3 above = x - hi;
  vec3 d = max(max(below, above), vec3(0.0f));
  return dot3(d, d);
}

// Squared distance from x to the farthest point of the box: sum over axes of
// max(|lo - x|, |hi - x|)^2 (RTSLC's dmax^2).
SST_FUNC float box_distance2_max(vec3 lo, vec3 hi, vec3 x) {
  SST_PRECISE vec3 a = lo - x;
  SST_PRECISE vec3 b = hi - x;
  vec3 d = max(abs(a), abs(b));
  return dot3(d, d);
}

// Smallest |t| over [lo, hi]: 0 when the interval straddles 0.
SST_FUNC float box_min_abs(float lo, float hi) { return lo <= 0.0f && hi >= 0.0f ? 0.0f : min(abs(lo), abs(hi)); }

// Upper bounds of max(0, n . normalize(y - x)) over the points y of the box, 1 when x is inside.
// Both are conservative; they trade tightness for cost:
// - box_cos_bound (Walter 2005): the corners are taken to n's basis and the bound is that of the
//   AABB of the transformed corners. Tight; used by slc and sst.
// - box_cos_bound_linear: min(1, max_y n.(y - x) / dmin), the exact maximum of a linear function
//   over the box over a lower bound of |y - x|. Cheap, tight for far boxes; used by rtslc's
//   weights and the cuts.
// The range over the box's corners c of dot3(c - x, a), given dl = lo - x and dh = hi - x: the
// scalar form of each lane of box_cos_bound_in_frame (tests/core/math/lanes_test.cpp holds the
// lanes to it). A corner's dot3 is a sum of one product per axis, added in dot3's order, and
// rounding is monotone, so the extremes are the sums of the per-axis extremes: the 8 corners'
// values, to the bit.
SST_FUNC vec2 box_corner_dot_range(vec3 dl, vec3 dh, vec3 a) {
  SST_PRECISE vec3 pl = dl * a;
  SST_PRECISE vec3 ph = dh * a;
  vec3 mn = min(pl, ph);
  vec3 mx = max(pl, ph);
  SST_PRECISE float lo = mn.x + mn.y + mn.z;
  SST_PRECISE float hi = mx.x + mx.y + mx.z;
  return vec2(lo, hi);
}

// box_cos_bound with n's basis `frame` = basis_from_normal(n) given: a walk takes it from its
// shading point instead of building it at every node. The box_corner_dot_range of the frame's
// three axes run side by side in lanes (lane j: axis j of t, b, n; lane 3 unused), each lane with
// box_corner_dot_range's products and sums in its order, so the bits are the same: a third of the
// operations, in SIMD registers on the CPU (lanes4, cpu_gpu.h).
SST_FUNC float box_cos_bound_in_frame(vec3 lo, vec3 hi, vec3 x, SST_IN(Basis) frame) {
  if (box_empty(lo, hi)) return 0.0f;
  if (box_inside(lo, hi, x)) return 1.0f;
  SST_PRECISE vec3 dl = lo - x;
  SST_PRECISE vec3 dh = hi - x;
  lanes4 ax = lanes4(frame.t.x, frame.b.x, frame.n.x, 0.0f);
  lanes4 ay = lanes4(frame.t.y, frame.b.y, frame.n.y, 0.0f);
  lanes4 az = lanes4(frame.t.z, frame.b.z, frame.n.z, 0.0f);
  SST_PRECISE lanes4 plx = dl.x * ax;
  SST_PRECISE lanes4 ply = dl.y * ay;
  SST_PRECISE lanes4 plz = dl.z * az;
  SST_PRECISE lanes4 phx = dh.x * ax;
  SST_PRECISE lanes4 phy = dh.y * ay;
  SST_PRECISE lanes4 phz = dh.z * az;
  // The box of the corners in the frame: lanes 0, 1, 2 of llo and lhi.
  SST_PRECISE lanes4 llo = min(plx, phx) + min(ply, phy) + min(plz, phz);
  SST_PRECISE lanes4 lhi = max(plx, phx) + max(ply, phy) + max(plz, phz);
  float hz = lhi[2];
  if (!(hz > 0.0f)) return 0.0f;  // wholly below the tangent plane
  float dx = box_min_abs(llo[0], lhi[0]);
  float dy = box_min_abs(llo[1], lhi[1]);
  SST_PRECISE float len2 = dx * dx + dy * dy + hz * hz;
  return len2 > 0.0f ? min(1.0f, hz / sqrt(len2)) : 1.0f;
}

SST_FUNC float box_cos_bound(vec3 lo, vec3 hi, vec3 x, vec3 n) {
  return box_cos_bound_in_frame(lo, hi, x, basis_from_normal(n));
}

SST_FUNC float box_cos_bound_linear(vec3 lo, vec3 hi, vec3 x, vec3 n) {
  float d2 = box_distance2_min(lo, hi, x);
  if (!(d2 > 0.0f)) return 1.0f;  // x in the box: every direction may occur
  SST_PRECISE vec3 l = lo - x;
  SST_PRECISE vec3 h = hi - x;
  // max over the box of n . (y - x): per axis the larger of the two ends.
  SST_PRECISE vec3 nl = n * l;
  SST_PRECISE vec3 nh = n * h;
  SST_PRECISE float zmax = max(nl.x, nh.x) + max(nl.y, nh.y) + max(nl.z, nh.z);
  if (!(zmax > 0.0f)) return 0.0f;
  return min(1.0f, zmax / sqrt(d2));
}

SST_END

#ifdef __cplusplus
#include "core/math/math.h"
namespace sst {
// The same bounds for a C++ Bounds3.
inline float box_distance2_min(const Bounds3& b, vec3 x) { return box_distance2_min(b.lo, b.hi, x); }
inline float box_distance2_max(const Bounds3& b, vec3 x) { return box_distance2_max(b.lo, b.hi, x); }
inline float box_cos_bound(const Bounds3& b, vec3 x, vec3 n) { return box_cos_bound(b.lo, b.hi, x, n); }
inline float box_cos_bound_linear(const Bounds3& b, vec3 x, vec3 n) { return box_cos_bound_linear(b.lo, b.hi, x, n); }
}  // namespace sst
#endif

#endif  // SST_CORE_MATH_BOX_BOUNDS_H
