// `slc`, stochastic lightcuts with one sample per cut (Yuksel 2019; docs/design/methods.md), the
// estimate at one shading point (shared C++/GLSL source; slc_sampler.h is the method). Walks the
// tree from the root to a leaf with Yuksel's child weights (core/lights/slc_weights.h, with the
// luminance of each node's summed VPL intensity) and shades the leaf's VPL divided by the walk's
// probability.
#ifndef SST_CORE_MANYLIGHT_SLC_SLC_ESTIMATE_H
#define SST_CORE_MANYLIGHT_SLC_SLC_ESTIMATE_H
#include "core/lights/slc_weights.h"
#include "core/manylight/estimator.h"

SST_BEGIN

// (w_left, w_right) at shading position x with shading frame `frame` (basis_from_normal of the
// shading normal; rtslc's `weights slc` too); floor_fraction: LightTreeParams::node_distance_floor.
SST_FUNC vec2 slc_child_weights(SST_IN(LightNode) left, SST_IN(LightNode) right, vec3 x, SST_IN(Basis) frame,
                                float floor_fraction) {
  SST_PRECISE float lum_left = luminance(left.intensity);
  SST_PRECISE float lum_right = luminance(right.intensity);
  return slc_pair_weights(left.bounds_lo, left.bounds_hi, lum_left, light_node_empty(left), right.bounds_lo,
                          right.bounds_hi, lum_right, light_node_empty(right), x, frame, floor_fraction);
}

SST_FUNC IndirectEstimate estimate_slc(ML_CTX_PARAM SST_IN(ShadingPoint) sp, SST_INOUT(PixelSampler) ps) {
  IndirectEstimate e = indirect_estimate_zero();
  TreeWalk walk = tree_walk_begin(ML_PARAMS.tree_root);
  // A walk visits every node at most once; the bound only guards against a malformed tree.
  for (uint step = 0u; step < ML_PARAMS.tree_node_count && walk.node != kNoNode; ++step) {
    walk.nodes_visited += 1u;
    LightNode node = ML_NODE(walk.node);
    if (light_node_is_leaf(node)) {
      uint vpl = node.left;
      if (vpl == kNoNode || vpl >= ML_PARAMS.vpl_count) break;  // a padding leaf (weight 0)
      if (!(walk.probability.m > 0.0f)) break;
      vec3 c = shade_vpl(ML_CTX sp, ML_VPL(vpl), e.shadow_rays);
      e.value = divide_by_probability(c, walk.probability);
      break;
    }
    vec2 w = slc_child_weights(ML_NODE(node.left), ML_NODE(node.right), sp.p, sp.basis, ML_PARAMS.node_distance_floor);
    tree_walk_step(walk, node, w, ps);
  }
  e.nodes_visited = walk.nodes_visited;
  return e;
}

SST_END

#endif  // SST_CORE_MANYLIGHT_SLC_SLC_ESTIMATE_H
