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

// box_distance2_min floored at (floor_fraction x the box's diagonal)^2: the node-distance floor
// of the tree methods (LightTreeParams::node_distance_floor). A bound of 1/d^2 over a box is
// meaningless where x is within the box's own size; the floor keeps a near box's weight to what
// its light could give from a fraction of its size away, so a box kilometres wide that holds x
// does not outweigh a small bright one beside it by its power alone. 0: the plain distance.
SST_FUNC float box_distance2_floored(vec3 lo, vec3 hi, vec3 x, float floor_fraction) {
  SST_PRECISE float f2 = floor_fraction * floor_fraction;
  SST_PRECISE float floor2 = f2 * box_diagonal2(lo, hi);
  return max(box_distance2_min(lo, hi, x), floor2);
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

// The box of the corners of [lo, hi] - x in the frame's coordinates: lanes 0, 1, 2 of llo and lhi
// hold box_corner_dot_range for the axes t, b, n (lane 3 unused). The three ranges run side by
// side, each lane with box_corner_dot_range's products and sums in its order, so the bits are the
// same: a third of the operations, in SIMD registers on the CPU (lanes4, cpu_gpu.h).
SST_FUNC void box_corners_in_frame(vec3 lo, vec3 hi, vec3 x, SST_IN(Basis) frame, SST_OUT(lanes4) llo,
                                   SST_OUT(lanes4) lhi) {
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
  SST_PRECISE lanes4 lo_sum = min(plx, phx) + min(ply, phy) + min(plz, phz);
  SST_PRECISE lanes4 hi_sum = max(plx, phx) + max(ply, phy) + max(plz, phz);
  llo = lo_sum;
  lhi = hi_sum;
}

// The last steps of the cosine bound for up to four boxes side by side (lane k: box k), from
// their corner boxes in the frame: the ranges along t (tlo, thi) and b (blo, bhi) and the top hz
// along n. Returns min(1, hz / |p|), p the corner box's point nearest to the normal's axis, and
// |p|^2 in len2; valid where hz > 0 and len2 > 0 (box_cos_bound_pick). An interval [lo, hi] lies
// max(lo, 0) + max(-hi, 0) from 0: box_min_abs's value up to the sign of a zero, which the squares
// drop, without its branch.
SST_FUNC lanes4 box_cos_bound_lanes(lanes4 tlo, lanes4 thi, lanes4 blo, lanes4 bhi, lanes4 hz, SST_OUT(lanes4) len2) {
  lanes4 zero = lanes4(0.0f, 0.0f, 0.0f, 0.0f);
  SST_PRECISE lanes4 dx = max(tlo, zero) + max(zero - thi, zero);
  SST_PRECISE lanes4 dy = max(blo, zero) + max(zero - bhi, zero);
  SST_PRECISE lanes4 l2 = dx * dx + dy * dy + hz * hz;
  len2 = l2;
  SST_PRECISE lanes4 q = hz / sqrt(l2);
  return min(lanes4(1.0f, 1.0f, 1.0f, 1.0f), q);
}

// One box's bound from its lane of box_cos_bound_lanes (c, len2) and its top hz: 0 for an empty box
// or one wholly below the tangent plane, 1 when x is inside it.
SST_FUNC float box_cos_bound_pick(vec3 lo, vec3 hi, vec3 x, float hz, float len2, float c) {
  if (box_empty(lo, hi)) return 0.0f;
  if (box_inside(lo, hi, x)) return 1.0f;
  if (!(hz > 0.0f)) return 0.0f;
  return len2 > 0.0f ? c : 1.0f;
}

// box_cos_bound with n's basis `frame` = basis_from_normal(n) given: a walk takes it from its
// shading point instead of building it at every node.
SST_FUNC float box_cos_bound_in_frame(vec3 lo, vec3 hi, vec3 x, SST_IN(Basis) frame) {
  lanes4 llo;
  lanes4 lhi;
  box_corners_in_frame(lo, hi, x, frame, llo, lhi);
  lanes4 len2;
  lanes4 c = box_cos_bound_lanes(lanes4(llo[0], 0.0f, 0.0f, 0.0f), lanes4(lhi[0], 0.0f, 0.0f, 0.0f),
                                 lanes4(llo[1], 0.0f, 0.0f, 0.0f), lanes4(lhi[1], 0.0f, 0.0f, 0.0f),
                                 lanes4(lhi[2], 0.0f, 0.0f, 0.0f), len2);
  return box_cos_bound_pick(lo, hi, x, lhi[2], len2[0], c[0]);
}

// box_cos_bound_in_frame of two boxes, their last steps side by side.
SST_FUNC vec2 box_cos_bound_pair_in_frame(vec3 lo0, vec3 hi0, vec3 lo1, vec3 hi1, vec3 x, SST_IN(Basis) frame) {
  lanes4 llo0;
  lanes4 lhi0;
  lanes4 llo1;
  lanes4 lhi1;
  box_corners_in_frame(lo0, hi0, x, frame, llo0, lhi0);
  box_corners_in_frame(lo1, hi1, x, frame, llo1, lhi1);
  lanes4 len2;
  lanes4 c = box_cos_bound_lanes(lanes4(llo0[0], llo1[0], 0.0f, 0.0f), lanes4(lhi0[0], lhi1[0], 0.0f, 0.0f),
                                 lanes4(llo0[1], llo1[1], 0.0f, 0.0f), lanes4(lhi0[1], lhi1[1], 0.0f, 0.0f),
                                 lanes4(lhi0[2], lhi1[2], 0.0f, 0.0f), len2);
  return vec2(box_cos_bound_pick(lo0, hi0, x, lhi0[2], len2[0], c[0]),
              box_cos_bound_pick(lo1, hi1, x, lhi1[2], len2[1], c[1]));
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
