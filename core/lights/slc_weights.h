// Yuksel's stochastic-lightcut child weights (SLC, Yuksel 2019; docs/design/methods.md) for two
// boxes of light, in the common subset of C++ and GLSL: the one text behind `slc` over VPL trees
// (core/manylight/slc) and the `slc` light sampler over the emitter tree (core/lights/emitter_tree.h).
//   w_i = lum_i * cosbound_i / dmin_i^2
// where cosbound_i bounds the receiver's cosine over box i (1 inside it) and dmin_i is the
// distance from x to the box. Yuksel's rule for boxes near x: when x is within one box diagonal
// of either box, distance is ignored for both (the 1/d^2 bound is meaningless there and would
// starve the sibling). With a node-distance floor f > 0 instead (box_distance2_floored), each
// distance is at least f times its box's diagonal and the rule is not applied: Yuksel's rule
// weighs a box kilometres wide that holds x by its power alone, against a bright room beside it.
#ifndef SST_CORE_LIGHTS_SLC_WEIGHTS_H
#define SST_CORE_LIGHTS_SLC_WEIGHTS_H
#include "core/math/box_bounds.h"

SST_BEGIN

// (w_0, w_1) at shading position x with shading normal n for boxes [lo_k, hi_k] of luminance
// lum_k; an empty box (no light below it) weighs 0 and never makes x "near". floor_fraction: the
// node-distance floor f (0: Yuksel's rule).
SST_FUNC vec2 slc_pair_weights(vec3 lo0, vec3 hi0, float lum0, bool empty0, vec3 lo1, vec3 hi1, float lum1,
                               bool empty1, vec3 x, SST_IN(Basis) frame, float floor_fraction) {
  vec2 cos_bound = box_cos_bound_pair_in_frame(lo0, hi0, lo1, hi1, x, frame);
  SST_PRECISE float b0 = lum0 * cos_bound.x;
  SST_PRECISE float b1 = lum1 * cos_bound.y;
  float base0 = empty0 ? 0.0f : b0;
  float base1 = empty1 ? 0.0f : b1;
  float d2_0 = empty0 ? 0.0f : box_distance2_floored(lo0, hi0, x, floor_fraction);
  float d2_1 = empty1 ? 0.0f : box_distance2_floored(lo1, hi1, x, floor_fraction);
  // With a floor only a distance of 0 (a point box at x itself) is near; <= rather than <: a
  // point box (diagonal 0) at x itself must not divide by 0.
  bool yuksel = !(floor_fraction > 0.0f);
  float near0 = yuksel ? box_diagonal2(lo0, hi0) : 0.0f;
  float near1 = yuksel ? box_diagonal2(lo1, hi1) : 0.0f;
  bool near = (!empty0 && d2_0 <= near0) || (!empty1 && d2_1 <= near1);
  if (near) return vec2(base0, base1);
  SST_PRECISE lanes4 w = lanes4(base0, base1, 0.0f, 0.0f) / lanes4(d2_0, d2_1, 1.0f, 1.0f);
  return vec2(base0 > 0.0f ? w[0] : 0.0f, base1 > 0.0f ? w[1] : 0.0f);
}

SST_END

#endif  // SST_CORE_LIGHTS_SLC_WEIGHTS_H
