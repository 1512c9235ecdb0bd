// `rtslc`, Real-Time Stochastic Lightcuts (Lin & Yuksel 2020), the estimate at one shading point
// (shared C++/GLSL source; rtslc_sampler.h is the method: the tree, the per-block cuts, the
// parameters). The pixel's block has a cut (built at a random pivot pixel); the pixel walks once
// from each of its cut nodes (every r^2-th with interleaving) to a leaf and sums the one-VPL
// estimates, each times r^2 / its walk's probability. Float throughout, as the paper's GPU code.
#ifndef SST_CORE_MANYLIGHT_RTSLC_RTSLC_ESTIMATE_H
#define SST_CORE_MANYLIGHT_RTSLC_RTSLC_ESTIMATE_H
#include "core/math/box_bounds.h"
#include "core/manylight/estimator.h"
#include "core/manylight/slc/slc_estimate.h"

SST_BEGIN

// lum(I) times the cheap cosine bound over the box: the paper's importance without distance.
SST_FUNC float rtslc_importance(SST_IN(LightNode) c, vec3 x, vec3 n) {
  SST_PRECISE float i = luminance(c.intensity) * box_cos_bound_linear(c.bounds_lo, c.bounds_hi, x, n);
  return light_node_empty(c) ? 0.0f : i;
}

// d1^2 IG0 / (d1^2 IG0 + d0^2 IG1), or `fallback` where that is not finite: a zero denominator
// (a zero-distance side with zero importance) carries no distance information.
SST_FUNC float rtslc_distance_weight(float ig0, float ig1, float d0, float d1, float fallback) {
  SST_PRECISE float a = d1 * ig0;
  SST_PRECISE float den = a + d0 * ig1;
  if (!(den > 0.0f)) return fallback;
  float w = a / den;
  return is_finite(w) ? w : fallback;
}

// P_0, the probability of descending into c0 rather than c1: the mean of the weights with the
// minimum and with the maximum distances to the boxes (Lin & Yuksel 2020, eq. 5), the minimum
// floored at floor_fraction times the box's diagonal (LightTreeParams::node_distance_floor).
SST_FUNC float rtslc_child_probability(SST_IN(LightNode) c0, SST_IN(LightNode) c1, vec3 x, vec3 n,
                                       float floor_fraction) {
  if (light_node_empty(c0)) return 0.0f;
  if (light_node_empty(c1)) return 1.0f;
  float ig0 = rtslc_importance(c0, x, n);
  float ig1 = rtslc_importance(c1, x, n);
  SST_PRECISE float ig = ig0 + ig1;
  if (!(ig > 0.0f)) return 0.0f;  // dead branch: neither child can light x
  float ratio = ig0 / ig;
  float dmin0 = box_distance2_floored(c0.bounds_lo, c0.bounds_hi, x, floor_fraction);
  float dmin1 = box_distance2_floored(c1.bounds_lo, c1.bounds_hi, x, floor_fraction);
  if (dmin0 == 0.0f && dmin1 == 0.0f) return ratio;  // x in both boxes: distance says nothing
  float wmax = rtslc_distance_weight(ig0, ig1, dmin0, dmin1, ratio);
  float wmin = rtslc_distance_weight(ig0, ig1, box_distance2_max(c0.bounds_lo, c0.bounds_hi, x),
                                     box_distance2_max(c1.bounds_lo, c1.bounds_hi, x), ratio);
  SST_PRECISE float mean = 0.5f * (wmax + wmin);
  return clamp(mean, 0.0f, 1.0f);
}

// (P_0, P_1) at an internal node with children c0, c1 (ML_PARAMS.rtslc_weights says whose
// weights; floor_fraction: LightTreeParams::node_distance_floor); both 0 for a dead branch, where
// no VPL below can light x. P_1 = 1 - P_0 exactly: the walk takes c0 iff u < P_0.
SST_FUNC vec2 rtslc_child_probabilities(SST_IN(LightNode) c0, SST_IN(LightNode) c1, vec3 x, vec3 n, uint weights,
                                        float floor_fraction) {
  if (weights == ML_RTSLC_WEIGHTS_SLC) {
    vec2 w = slc_child_weights(c0, c1, x, basis_from_normal(n), floor_fraction);
    float sum = w.x + w.y;
    if (!(sum > 0.0f) || !is_finite(sum)) return vec2(0.0f);
    float p0 = w.x / sum;
    return vec2(p0, 1.0f - p0);
  }
  SST_PRECISE float ig = rtslc_importance(c0, x, n) + rtslc_importance(c1, x, n);
  if (!(ig > 0.0f)) return vec2(0.0f);
  float p0 = rtslc_child_probability(c0, c1, x, n, floor_fraction);
  return vec2(p0, 1.0f - p0);
}

// The error a cut node is split by: lum(I) cosbound / max(dmin^2, min_distance^2) seen from the
// block's pivot sample (x, n).
SST_FUNC float rtslc_cut_error(SST_IN(LightNode) node, vec3 x, vec3 n, float min_distance) {
  if (light_node_empty(node)) return 0.0f;
  SST_PRECISE float m2 = min_distance * min_distance;
  float d2 = max(box_distance2_min(node.bounds_lo, node.bounds_hi, x), m2);
  SST_PRECISE float e = luminance(node.intensity) * box_cos_bound_linear(node.bounds_lo, node.bounds_hi, x, n) / d2;
  return e;
}

struct RtslcSample {
  uint node;  // the leaf reached; kNoNode: a dead branch
  float probability;
  uint nodes_visited;
};

// One stochastic descent from node `from` to a leaf.
SST_FUNC RtslcSample rtslc_traverse(ML_CTX_PARAM uint from, vec3 x, vec3 n, SST_INOUT(PixelSampler) ps) {
  RtslcSample s;
  s.node = kNoNode;
  s.probability = 0.0f;
  s.nodes_visited = 0u;
  uint i = from;
  float prob = 1.0f;
  for (uint step = 0u; step < ML_PARAMS.tree_node_count; ++step) {  // bound: a malformed tree
    s.nodes_visited += 1u;
    LightNode node = ML_NODE(i);
    if (light_node_is_leaf(node)) {
      if (!(prob > 0.0f) || light_node_empty(node)) return s;
      s.node = i;
      s.probability = prob;
      return s;
    }
    vec2 p = rtslc_child_probabilities(ML_NODE(node.left), ML_NODE(node.right), x, n, ML_PARAMS.rtslc_weights,
                                       ML_PARAMS.node_distance_floor);
    if (!(p.x + p.y > 0.0f)) return s;  // dead branch: no estimate, no shadow ray
    bool left = pixel_sampler_get1d(ps) < p.x;
    prob *= left ? p.x : p.y;
    i = left ? node.left : node.right;
  }
  return s;
}

// Where pixel sp's share of its block's cut is: the cut nodes i = slot, slot + slots, ... (slots =
// r^2 with interleaving rate r; every node without), each estimate weighted by slots. The VPL cut
// and the emitter cut (rtslc_direct.h) of a block are shared out alike.
struct RtslcPixelShare {
  uint block;
  uint slot;
  uint slots;
};

SST_FUNC RtslcPixelShare rtslc_pixel_share(ML_CTX_PARAM SST_IN(ShadingPoint) sp) {
  RtslcPixelShare share;
  uint r = ML_PARAMS.rtslc_interleave;
  uint x = uint(sp.x);
  uint y = uint(sp.y);
  share.slots = r * r;
  share.slot = (r * (y % r) + x % r + ML_PARAMS.rtslc_frame_index) % share.slots;
  share.block = (y / ML_PARAMS.cut_block_size) * ML_PARAMS.cut_blocks_x + x / ML_PARAMS.cut_block_size;
  return share;
}

SST_FUNC IndirectEstimate estimate_rtslc(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_INOUT(PixelSampler) ps) {
  IndirectEstimate e = indirect_estimate_zero();
  if (ML_PARAMS.tree_root == kNoNode) return e;
  RtslcPixelShare share = rtslc_pixel_share(ML_CTX sp);
  uint slots = share.slots;
  uint first = share.block * ML_PARAMS.cut_max_size;
  uint size = ML_CUT_SIZE(share.block);
  for (uint i = share.slot; i < size; i += slots) {
    RtslcSample s = rtslc_traverse(ML_CTX ML_CUT_NODE(first + i), sp.p, sp.basis.n, ps);
    e.nodes_visited += s.nodes_visited;
    if (s.node == kNoNode) continue;
    vec3 c = shade_vpl(ML_CTX sp, ML_VPL(ML_NODE(s.node).left), e.shadow_rays);
    SST_PRECISE float weight = float(slots) / s.probability;
    SST_PRECISE vec3 v = c * weight;
    e.value += v;
  }
  return e;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_RTSLC_RTSLC_ESTIMATE_H
