// The GLSL twin of core/manylight/rtslc_sampler.cpp: `rtslc`, Real-Time Stochastic Lightcuts
// (Lin & Yuksel 2020). The pixel's block has a cut (built on the CPU at a random pivot pixel,
// uploaded); the pixel walks once from each of its cut nodes (every r^2-th with interleaving) to
// a leaf and sums the one-VPL estimates, each times r^2 / its walk's probability. Float
// throughout, as on the CPU, except `weights slc`, whose child weights the CPU takes in double
// (slc_child_weights) before rounding P_0 to float; here they are float.
#ifndef SST_GPU_SHADERS_INDIRECT_RTSLC_GLSL
#define SST_GPU_SHADERS_INDIRECT_RTSLC_GLSL
#include "core/lighttree/box_bounds.h"
#include "gpu/shaders/indirect/slc.glsl"

float rtslc_importance(LightNode c, vec3 x, vec3 n) {
  precise float i = luminance(c.intensity) * box_cos_bound_linear(c.bounds_lo, c.bounds_hi, x, n);
  return node_empty(c) ? 0.0 : i;
}

// d1^2 IG0 / (d1^2 IG0 + d0^2 IG1), or `fallback` where the CPU's value is not finite (a zero
// denominator: no distance information).
float rtslc_distance_weight(float ig0, float ig1, float d0, float d1, float fallback) {
  precise float a = d1 * ig0;
  precise float den = a + d0 * ig1;
  if (!(den > 0.0)) return fallback;
  float w = a / den;
  return is_finite(w) ? w : fallback;
}

// rtslc_child_probability: P_0, the probability of descending into c0 rather than c1.
float rtslc_child_probability(LightNode c0, LightNode c1, vec3 x, vec3 n) {
  if (node_empty(c0)) return 0.0;
  if (node_empty(c1)) return 1.0;
  float ig0 = rtslc_importance(c0, x, n), ig1 = rtslc_importance(c1, x, n);
  precise float ig = ig0 + ig1;
  if (!(ig > 0.0)) return 0.0;  // dead branch: neither child can light x
  float ratio = ig0 / ig;
  float dmin0 = box_distance2_min(c0.bounds_lo, c0.bounds_hi, x);
  float dmin1 = box_distance2_min(c1.bounds_lo, c1.bounds_hi, x);
  if (dmin0 == 0.0 && dmin1 == 0.0) return ratio;  // x in both boxes: distance says nothing
  float wmax = rtslc_distance_weight(ig0, ig1, dmin0, dmin1, ratio);
  float wmin = rtslc_distance_weight(ig0, ig1, box_distance2_max(c0.bounds_lo, c0.bounds_hi, x),
                                     box_distance2_max(c1.bounds_lo, c1.bounds_hi, x), ratio);
  precise float mean = 0.5 * (wmax + wmin);
  return clamp(mean, 0.0, 1.0);
}

// (P_0, P_1) at an internal node; both 0 for a dead branch.
vec2 rtslc_child_probabilities(LightNode node, vec3 x, vec3 n) {
  LightNode c0 = ml_nodes[node.left], c1 = ml_nodes[node.right];
  if (ml_params.rtslc_weights == ML_RTSLC_WEIGHTS_SLC) {
    vec2 w = slc_child_weights(c0, c1, x, n);
    float sum = w.x + w.y;
    if (!(sum > 0.0) || !is_finite(sum)) return vec2(0.0);
    float p0 = w.x / sum;
    return vec2(p0, 1.0 - p0);
  }
  precise float ig = rtslc_importance(c0, x, n) + rtslc_importance(c1, x, n);
  if (!(ig > 0.0)) return vec2(0.0);
  float p0 = rtslc_child_probability(c0, c1, x, n);
  return vec2(p0, 1.0 - p0);
}

struct RtslcSample {
  uint node;  // the leaf reached; ML_NO_NODE: a dead branch
  float probability;
  uint nodes_visited;
};

// rtslc_traverse: one stochastic descent from `from` to a leaf.
RtslcSample rtslc_traverse(uint from, vec3 x, vec3 n, inout PixelSampler ps) {
  RtslcSample s = RtslcSample(ML_NO_NODE, 0.0, 0u);
  uint i = from;
  float prob = 1.0;
  for (uint step = 0u; step < ml_params.tree_node_count; ++step) {  // bound: a malformed tree
    ++s.nodes_visited;
    LightNode node = ml_nodes[i];
    if ((node.flags & ML_NODE_LEAF) != 0u) {
      if (!(prob > 0.0) || node_empty(node)) return s;
      s.node = i;
      s.probability = prob;
      return s;
    }
    vec2 p = rtslc_child_probabilities(node, x, n);
    if (!(p.x + p.y > 0.0)) return s;  // dead branch: no estimate, no shadow ray
    bool left = pixel_sampler_get1d(ps) < p.x;
    prob *= left ? p.x : p.y;
    i = left ? node.left : node.right;
  }
  return s;
}

IndirectEstimate estimate_rtslc(ShadingPoint sp, inout PixelSampler ps) {
  IndirectEstimate e = indirect_estimate_zero();
  if (ml_params.tree_root == ML_NO_NODE) return e;
  uint r = ml_params.rtslc_interleave, slots = r * r;
  uint x = uint(sp.x), y = uint(sp.y);
  uint slot = (r * (y % r) + x % r + ml_params.rtslc_frame_index) % slots;
  uint block = (y / ml_params.cut_block_size) * ml_params.cut_blocks_x + x / ml_params.cut_block_size;
  uint first = block * ml_params.cut_max_size, size = ml_cut_sizes[block];
  for (uint i = slot; i < size; i += slots) {
    RtslcSample s = rtslc_traverse(ml_cut_nodes[first + i], sp.p, sp.basis.n, ps);
    e.nodes_visited += s.nodes_visited;
    if (s.node == ML_NO_NODE) continue;
    vec3 c = shade_vpl(sp, ml_vpl(ml_nodes[s.node].left), e.shadow_rays);
    precise float weight = float(slots) / s.probability;
    precise vec3 v = c * weight;
    e.value += v;
  }
  return e;
}

#endif
