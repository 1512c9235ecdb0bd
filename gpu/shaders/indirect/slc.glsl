// The GLSL twin of core/manylight/slc_sampler.cpp: `slc`, stochastic lightcuts with one sample
// per cut (Yuksel 2019). Walks the tree from the root to a leaf with Yuksel's child weights
//   w_i = lum(I_i) * cosbound_i / dmin_i^2   (distance ignored for both when x is within one box
//                                             diagonal of either child)
// and shades the leaf's VPL divided by the walk's probability.
// The weights are float here, double on the CPU (see tree_walk.glsl).
#ifndef SST_GPU_SHADERS_INDIRECT_SLC_GLSL
#define SST_GPU_SHADERS_INDIRECT_SLC_GLSL
#include "core/lighttree/box_bounds.h"
#include "gpu/shaders/indirect/tree_walk.glsl"

bool node_empty(LightNode node) { return node.vpl_count == 0u; }

// slc_child_weights: (w_left, w_right) at shading position x with shading normal n.
vec2 slc_child_weights(LightNode left, LightNode right, vec3 x, vec3 n) {
  float base[2], d2[2];
  bool near = false;
  for (int k = 0; k < 2; ++k) {
    LightNode node = k == 0 ? left : right;
    bool empty = node_empty(node);
    precise float b = luminance(node.intensity) * box_cos_bound(node.bounds_lo, node.bounds_hi, x, n);
    base[k] = empty ? 0.0 : b;
    d2[k] = empty ? 0.0 : box_distance2_min(node.bounds_lo, node.bounds_hi, x);
    float diag = box_diagonal(node.bounds_lo, node.bounds_hi);
    // <= rather than <: a point box (diag 0) at x itself must not divide by 0.
    precise float diag2 = diag * diag;
    if (!empty && d2[k] <= diag2) near = true;
  }
  if (near) return vec2(base[0], base[1]);
  return vec2(base[0] > 0.0 ? base[0] / d2[0] : 0.0, base[1] > 0.0 ? base[1] / d2[1] : 0.0);
}

IndirectEstimate estimate_slc(ShadingPoint sp, inout PixelSampler ps) {
  IndirectEstimate e = indirect_estimate_zero();
  TreeWalk walk = TreeWalk(TREE_WEIGHTS_SLC, 0.0, false, false);
  TreeTraversal t = traverse_tree(sp, walk, ps);
  e.nodes_visited = t.nodes_visited;
  if (t.node == ML_NO_NODE || !tree_probability_positive(t.probability)) return e;
  uint vpl = ml_nodes[t.node].left;
  if (vpl == ML_NO_NODE || vpl >= ml_params.vpl_count) return e;  // a padding leaf (weight 0)
  vec3 c = shade_vpl(sp, ml_vpl(vpl), e.shadow_rays);
  e.value = divide_by_probability(c, t.probability);
  return e;
}

#endif
