// Yuksel's stochastic-lightcut child weights (SLC, Yuksel 2019; METHODS.md section 3) for two
// boxes of light, in the common subset of C++ and GLSL: the one text behind `slc` over VPL trees
// (core/manylight/slc) and the `slc` light sampler over the emitter tree (core/lights/emitter_tree.h).
//   w_i = lum_i * cosbound_i / dmin_i^2
// where cosbound_i bounds the receiver's cosine over box i (1 inside it) and dmin_i is the
// distance from x to the box; when x is within one box diagonal of either box, distance is ignored
// for both (the 1/d^2 bound is meaningless there and would starve the sibling).
#ifndef SST_CORE_LIGHTS_SLC_WEIGHTS_H
#define SST_CORE_LIGHTS_SLC_WEIGHTS_H
#include "core/math/box_bounds.h"

SST_BEGIN

// (w_0, w_1) at shading position x with shading normal n for boxes [lo_k, hi_k] of luminance
// lum_k; an empty box (no light below it) weighs 0 and never makes x "near".
SST_FUNC vec2 slc_pair_weights(vec3 lo0, vec3 hi0, float lum0, bool empty0, vec3 lo1, vec3 hi1, float lum1,
                               bool empty1, vec3 x, SST_IN(Basis) frame) {
  float base[2];
  float d2[2];
  bool near = false;
  for (int k = 0; k < 2; ++k) {
    vec3 lo = k == 0 ? lo0 : lo1;
    vec3 hi = k == 0 ? hi0 : hi1;
    bool empty = k == 0 ? empty0 : empty1;
    SST_PRECISE float b = (k == 0 ? lum0 : lum1) * box_cos_bound_in_frame(lo, hi, x, frame);
    base[k] = empty ? 0.0f : b;
    d2[k] = empty ? 0.0f : box_distance2_min(lo, hi, x);
    // <= rather than <: a point box (diagonal 0) at x itself must not divide by 0.
    if (!empty && d2[k] <= box_diagonal2(lo, hi)) near = true;
  }
  if (near) return vec2(base[0], base[1]);
  return vec2(base[0] > 0.0f ? base[0] / d2[0] : 0.0f, base[1] > 0.0f ? base[1] / d2[1] : 0.0f);
}

SST_END

#endif  // SST_CORE_LIGHTS_SLC_WEIGHTS_H
