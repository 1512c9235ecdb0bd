// Picking a light for a shading point down the emitter tree, in the common subset of C++ and GLSL:
// the `tree` and `slc` light samplers (LIGHT_SAMPLER_TREE, LIGHT_SAMPLER_SLC). The tree
// (core/lights/emitter_tree_build.h builds it; core/lights/light_layout.h's EmitterNode) holds
// every emissive triangle and every point and spot light as a leaf; directional lights stand
// beside it. A pick first chooses among the directional lights and the tree's root, then walks
// from the root to a leaf choosing each child in proportion to its weight, and reports the
// product of the choices' probabilities; emitter_tree_pmf recomputes that product for a given
// light with the same arithmetic, so a pick's pmf and the pmf of the light it picked are the
// same float (pbrt-v4's BVHLightSampler::PMF(ctx, light), for MIS with BSDF sampling).
//
// Weights, for a shading point p with shading normal n:
// - tree: the importance of pbrt-v4's LightBounds::Importance (after Conty Estevez & Kulla 2018):
//     intensity * cos(theta') / d^2 * cos_i
//   theta' = max(0, theta_w - theta_o - theta_b), where theta_w is the angle between the node's
//   axis and the direction from the box centre to p (its absolute value for two-sided emitters)
//   and theta_b the half angle the box's bounding sphere subtends from p; zero when
//   theta' >= theta_e (nothing is emitted that way). d^2 follows LightHeader.tree_distance
//   (RenderOptions::light_tree_distance), r being the radius of the box's bounding sphere:
//   - EMITTER_DISTANCE_CENTRE: the squared distance from p to the box's centre, at least
//     (r/4)^2, as pbrt-v4 measures it (pbrt clamps it at half the diagonal's length, a bound in
//     the scene's units). Inside a large node it still tells which part p is near.
//   - EMITTER_DISTANCE_BOX: the squared distance from p to the box, at least r^2: never less
//     than any emitter's distance, but flat wherever p lies within r of the box, so the walk's
//     upper levels, whose boxes hold p, choose by intensity alone. With the morton tree the
//     centre's distance had given a point beside one window of a long row the row's far
//     centre, the window a tiny probability, and the full path tracer fireflies (relative MSE
//     on the night street at 16 spp 0.76 against 0.35 with this distance; power 0.31).
//   - EMITTER_DISTANCE_MIXED: the box's distance outside the bounding sphere, the centre's
//     (clamped to [r^2/16, r^2]) within it: never less than `box`'s importance.
//   cos_i bounds the receiver cosine over the box itself (box_cos_bound_linear, core/math/box_bounds.h), where pbrt uses
//   cos(max(0, theta_i - theta_b)) over the bounding sphere: it is zero exactly when the whole
//   box is behind the surface (where sst's BRDFs reflect nothing), so an inner node is zero from
//   that side exactly when both children are. (Walks still end where an inner node's cone and
//   bounding sphere reach p and neither child's does: the pick returns no light, with the
//   probability 1 - sum of the pmfs, and the sample counts 0, as pbrt-v4's does. In
//   tests/core/lights/light_sampler_test.cpp that mass reaches 0.10 at a point among 2000 small
//   triangles and 0.7 among a few narrow spot lights; with pbrt's centre distance it was 0.08,
//   and 0.12 with pbrt's receiver bound as well.)
//   Directional lights: irradiance * max(0, n . -direction), the exact irradiance.
// - slc: Yuksel's child weights (core/lights/slc_weights.h) on the same boxes, with each node's
//   intensity; receiver cosine and distance only, no emitter orientation. The first choice (the
//   directional lights against the root) uses the tree importance in both samplers.
// Both weights are zero only where every light below the node sends nothing toward p or arrives
// from behind n: a light of probability 0 contributes 0.
//
// Hooks (core/lights/light_sample.h lists them): LIGHT_HEADER, LIGHT_CDF(i), LIGHT_TREE(i).
#ifndef SST_CORE_LIGHTS_EMITTER_TREE_H
#define SST_CORE_LIGHTS_EMITTER_TREE_H
#include "core/lights/light_layout.h"
#include "core/lights/slc_weights.h"
#include "core/math/box_bounds.h"
#include "core/math/vector_math.h"

// The light sampler in use (core/lights/light_sample.h lists this optional hook).
#ifndef LIGHT_SAMPLER_KIND
#define LIGHT_SAMPLER_KIND LIGHT_HEADER.sampler_kind
#endif

SST_BEGIN

// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of a, b in [0, pi].
SST_FUNC float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  if (cos_a > cos_b) return 1.0f;  // a < b
  SST_PRECISE float c = cos_a * cos_b + sin_a * sin_b;
  return c;
}
SST_FUNC float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
  if (cos_a > cos_b) return 0.0f;
  SST_PRECISE float s = sin_a * cos_b - cos_a * sin_b;
  return s;
}
SST_FUNC float sin_from_cos(float c) {
  SST_PRECISE float s2 = 1.0f - c * c;
  return sqrt(max(0.0f, s2));
}

// The tree weight of `node` for p, n (see the top) with distance rule `distance`
// (EMITTER_DISTANCE_*). n = 0: no receiver cosine.
SST_FUNC float emitter_importance(SST_IN(EmitterNode) node, vec3 p, vec3 n, uint distance) {
  if (!(node.intensity > 0.0f)) return 0.0f;
  if ((node.flags & EMITTER_DIRECTIONAL) != 0u) {
    float c = dot3(n, n) > 0.0f ? dot3(n, -node.axis) : 1.0f;
    return node.intensity * max(0.0f, c);
  }
  vec3 pc = (node.lo + node.hi) * 0.5f;
  vec3 half_extent = (node.hi - node.lo) * 0.5f;
  float r2 = dot3(half_extent, half_extent);
  vec3 to_p = p - pc;
  float d2_centre = dot3(to_p, to_p);
  // The box's bounding sphere from p: every direction when p is inside it.
  float cos_b = -1.0f;
  if (d2_centre > r2) {
    float sin2_b = r2 / d2_centre;
    cos_b = sqrt(max(0.0f, 1.0f - sin2_b));
  }
  float sin_b = sin_from_cos(cos_b);
  vec3 wi = d2_centre > 0.0f ? to_p / sqrt(d2_centre) : vec3(0.0f);  // from the box toward p
  float cos_w = dot3(node.axis, wi);
  if ((node.flags & EMITTER_TWO_SIDED) != 0u) cos_w = abs(cos_w);
  float sin_w = sin_from_cos(cos_w);
  float sin_o = sin_from_cos(node.cos_o);
  float cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, node.cos_o);
  float sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, node.cos_o);
  float cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
  if (cos_p <= node.cos_e) return 0.0f;
  float d2 = max(d2_centre, r2 * 0.0625f);
  if (distance == EMITTER_DISTANCE_BOX) d2 = max(box_distance2_min(node.lo, node.hi, p), r2);
  if (distance == EMITTER_DISTANCE_MIXED)
    d2 = max(box_distance2_min(node.lo, node.hi, p), clamp(d2_centre, r2 * 0.0625f, r2));
  float importance = node.intensity * cos_p / d2;
  if (dot3(n, n) > 0.0f) {
    float cos_i = box_cos_bound_linear(node.lo, node.hi, p, n);
    if (!(cos_i > 0.0f)) return 0.0f;
    importance *= cos_i;
  }
  return max(importance, 0.0f);
}

// (w_left, w_right) of the sibling pair at `first` and `first + 1` (an inner node's children) for
// p, n, under the header's sampler. Infinite weights (a point light at p) win over finite ones;
// NaN weighs 0.
SST_FUNC vec2 emitter_child_weights(LIGHT_CTX_PARAM uint first, vec3 p, vec3 n) {
  EmitterNode a = LIGHT_TREE(first);
  EmitterNode b = LIGHT_TREE(first + 1u);
  vec2 w;
  if (LIGHT_SAMPLER_KIND == LIGHT_SAMPLER_SLC) {
    w = slc_pair_weights(a.lo, a.hi, a.intensity, !(a.intensity > 0.0f), b.lo, b.hi, b.intensity,
                         !(b.intensity > 0.0f), p, basis_from_normal(n), 0.0f);
  } else {
    uint distance = LIGHT_HEADER.tree_distance;
    w = vec2(emitter_importance(a, p, n, distance), emitter_importance(b, p, n, distance));
  }
  if (isinf(w.x) || isinf(w.y)) w = vec2(isinf(w.x) ? 1.0f : 0.0f, isinf(w.y) ? 1.0f : 0.0f);
  if (isnan(w.x)) w.x = 0.0f;
  if (isnan(w.y)) w.y = 0.0f;
  return w;
}

// The first choice's candidates: directional light k < directional_count (node
// 2 tree_leaves + k), then the root (node 1) when there is a tree.
SST_FUNC uint emitter_top_node(LIGHT_CTX_PARAM uint k) {
  return k < LIGHT_HEADER.directional_count ? 2u * LIGHT_HEADER.tree_leaves + k : 1u;
}
SST_FUNC float emitter_top_importance(LIGHT_CTX_PARAM uint k, vec3 p, vec3 n) {
  float w = emitter_importance(LIGHT_TREE(emitter_top_node(LIGHT_CTX k)), p, n, LIGHT_HEADER.tree_distance);
  return is_finite(w) ? w : (isinf(w) ? 3.0e38f : 0.0f);
}
// Candidate k's weight, given the root's (`root`, from emitter_top_total): the root's importance
// is the costly one and is evaluated once per pick; a directional light's is a dot product.
SST_FUNC float emitter_top_weight(LIGHT_CTX_PARAM uint k, vec3 p, vec3 n, float root) {
  return k < LIGHT_HEADER.directional_count ? emitter_top_importance(LIGHT_CTX k, p, n) : root;
}
// The sum of the candidates' weights; `root` receives the root's (0 without a tree).
SST_FUNC float emitter_top_total(LIGHT_CTX_PARAM vec3 p, vec3 n, SST_OUT(float) root) {
  uint count = LIGHT_HEADER.directional_count;
  root = LIGHT_HEADER.tree_leaves > 0u ? emitter_top_importance(LIGHT_CTX count, p, n) : 0.0f;
  if (LIGHT_HEADER.tree_leaves > 0u) count += 1u;
  float total = 0.0f;
  for (uint k = 0u; k < count; ++k) total += emitter_top_weight(LIGHT_CTX k, p, n, root);
  return total;
}

// The walk from `node` (any node; a leaf or a directional light's node is the light itself) down to a leaf,
// each child chosen with u in [0, 1) in proportion to its weight for p, n: the leaf's
// distribution entry, or LIGHT_NONE where both children of a node weigh zero. `prob` is
// multiplied by each choice's probability and `u` is left at its position within the chosen
// leaf's share. emitter_tree_pick walks from the root; RTSLC's direct light from each node of a
// block's cut (core/manylight/rtslc/rtslc_direct.h).
SST_FUNC uint emitter_tree_descend(LIGHT_CTX_PARAM uint node, vec3 p, vec3 n, SST_INOUT(float) u, SST_INOUT(float) prob) {
  // Locals, not the references: in C++ a write through a float& may alias the tree's floats.
  float v = u;
  float q = prob;
  uint children = LIGHT_TREE(node).children;
  while (children != 0u) {
    vec2 cw = emitter_child_weights(LIGHT_CTX children, p, n);
    float sum = cw.x + cw.y;
    if (!(sum > 0.0f)) {
      u = v;
      prob = q;
      return LIGHT_NONE;
    }
    float p_left = cw.x / sum;
    float p_right = cw.y / sum;
    if (v < p_left) {
      node = children;
      v = min(v / p_left, kOneMinusEpsilon);
      q *= p_left;
    } else {
      node = children + 1u;
      v = clamp((v - p_left) / (1.0f - p_left), 0.0f, kOneMinusEpsilon);
      q *= p_right;
    }
    children = LIGHT_TREE(node).children;
  }
  u = v;
  prob = q;
  return LIGHT_TREE(node).entry;
}

// A light for p, n with u in [0, 1): its distribution entry, or LIGHT_NONE when every weight is
// zero (no light can contribute). `pmf` receives its probability, `u_remapped` u's position
// within the chosen light's share of [0, 1) (uniform; a pick loses about one bit of it per level).
SST_FUNC uint emitter_tree_pick(LIGHT_CTX_PARAM vec3 p, vec3 n, float u, SST_OUT(float) pmf,
                                SST_OUT(float) u_remapped) {
  pmf = 0.0f;
  u_remapped = 0.0f;
  float root = 0.0f;
  float total = emitter_top_total(LIGHT_CTX p, n, root);
  if (!(total > 0.0f) || !is_finite(total)) return LIGHT_NONE;
  uint count = LIGHT_HEADER.directional_count + (LIGHT_HEADER.tree_leaves > 0u ? 1u : 0u);
  // The candidate whose share of [0, total) holds u * total; the last one of positive weight
  // when rounding carries the target past every share.
  float target = u * total;
  float below = 0.0f;
  uint chosen = count;
  float w = 0.0f;
  for (uint k = 0u; k < count; ++k) {
    float wk = emitter_top_weight(LIGHT_CTX k, p, n, root);
    if (!(wk > 0.0f)) continue;
    chosen = k;
    w = wk;
    if (target < below + wk) break;
    below += wk;
  }
  if (chosen == count) return LIGHT_NONE;
  float prob = w / total;
  u = clamp((target - below) / w, 0.0f, kOneMinusEpsilon);
  uint node = emitter_top_node(LIGHT_CTX chosen);
  uint entry = emitter_tree_descend(LIGHT_CTX node, p, n, u, prob);
  if (entry == LIGHT_NONE || !(prob > 0.0f)) return LIGHT_NONE;
  pmf = prob;
  u_remapped = u;
  return entry;
}

// The probability that emitter_tree_pick(p, n, u) returns distribution entry `entry` for a
// uniform u, in `pmf`: the same products in the same order, so it equals the pick's pmf bit for
// bit. (An out parameter, not a return value: glslang carries `precise` from a caller's
// expression into the callee's return values, and through this loop that took minutes.)
SST_FUNC void emitter_tree_pmf(LIGHT_CTX_PARAM vec3 p, vec3 n, uint entry, SST_OUT(float) pmf) {
  pmf = 0.0f;
  if (entry >= LIGHT_HEADER.distribution_size) return;
  uint node = LIGHT_CDF(entry).tree_node;
  if (node == LIGHT_NONE) return;
  float root = 0.0f;
  float total = emitter_top_total(LIGHT_CTX p, n, root);
  if (!(total > 0.0f) || !is_finite(total)) return;
  uint leaves = LIGHT_HEADER.tree_leaves;
  uint top = node >= 2u * leaves ? node - 2u * leaves : LIGHT_HEADER.directional_count;
  float w = emitter_top_weight(LIGHT_CTX top, p, n, root);
  if (!(w > 0.0f)) return;
  float prob = w / total;
  if (node < 2u * leaves) {
    // The path from the root, read upward through the parents: bit k of (trail_lo, trail_hi) is
    // 1 where the path's node k levels above the leaf (k = 0: the leaf) is its parent's second
    // child; the build keeps the depth within kEmitterTreeMaxDepth = 64. Then the choices are
    // multiplied from the root down, as the pick multiplies them.
    uint trail_lo = 0u;
    uint trail_hi = 0u;
    uint depth = 0u;
    for (uint c = node; c != 1u && depth < 64u; ++depth) {
      uint parent = LIGHT_TREE(c).parent;
      uint bit = c - LIGHT_TREE(parent).children;
      if (depth < 32u) trail_lo |= bit << depth;
      else trail_hi |= bit << (depth - 32u);
      c = parent;
    }
    uint at = 1u;
    for (uint d = depth; d > 0u; --d) {
      uint k = d - 1u;
      uint bit = ((k < 32u ? trail_lo >> k : trail_hi >> (k - 32u)) & 1u);
      uint first = LIGHT_TREE(at).children;
      vec2 cw = emitter_child_weights(LIGHT_CTX first, p, n);
      float sum = cw.x + cw.y;
      if (!(sum > 0.0f)) return;
      float p_left = cw.x / sum;
      float p_right = cw.y / sum;
      prob *= bit == 0u ? p_left : p_right;
      at = first + bit;
    }
  }
  pmf = prob;
}

SST_END

#endif  // SST_CORE_LIGHTS_EMITTER_TREE_H
