// `slc`: stochastic lightcuts with one sample per cut (Yuksel 2019; METHODS.md §3). Walks the
// light tree from the root to a leaf, choosing child i with probability w_i / (w_1 + w_2),
//   w_i = lum(I_i) * cosbound_i / dmin_i^2,
// cosbound = upper bound of the cosine at x (shading normal) over the child's box, dmin = the
// distance from x to the box. When x is within one box diagonal of either child (dmin_i <=
// diag_i), distance is ignored for both (w_i = lum(I_i) * cosbound_i): the 1/d^2 bound is
// meaningless there and would starve the sibling. Unbiased w.r.t. exhaustive: a weight is 0
// only when every VPL below contributes 0 (no intensity, or the box is behind the surface).
//
// Also the shared tree-walk machinery of the tree samplers (sst reuses it): a generic traversal
// and the exact stop-node probabilities for tests.
#pragma once
#include <array>
#include <functional>

#include "core/lighttree/light_tree.h"
#include "core/manylight/indirect_sampler.h"
#include "core/manylight/tree_method_params.h"
#include "core/manylight/tree_sampler_base.h"

namespace sst {


// Child weights (w_left, w_right) of an internal node at a shading point.
using ChildWeights = std::function<std::array<double, 2>(const LightNode& left, const LightNode& right)>;
// Whether the walk stops at this node (leaves always stop).
using StopRule = std::function<bool(const LightNode& node)>;

struct TreeTraversal {
  uint32_t node = kNoNode;     // the stop node (leaf or, for sst, a suitable node); kNoNode: dead
  double probability = 0.0;    // of reaching `node` (product of the child probabilities)
  uint32_t nodes_visited = 0;  // nodes whose weights were evaluated, the root included
};

// Walks from tree.root; `u()` returns uniforms in [0, 1). A dead branch (w_1 + w_2 = 0, or a
// non-finite sum) ends the walk with node = kNoNode.
TreeTraversal traverse_tree(const LightTree& tree, const ChildWeights& weights, const StopRule& stop,
                            const std::function<float()>& u);
// The exact probability that traverse_tree stops at each node (indexed like tree.nodes; 0 for
// nodes it never stops at). Sums to 1 over the nodes unless some branch is dead. For tests.
std::vector<double> stop_probabilities(const LightTree& tree, const ChildWeights& weights, const StopRule& stop);

// c / p computed in double; 0 for p <= 0 or a non-finite result (never a NaN in the image).
vec3 divide_by_probability(vec3 c, double p);

// Yuksel's weights at shading position x with shading normal n (rtslc's `weights slc` uses them too).
std::array<double, 2> slc_child_weights(const LightNode& left, const LightNode& right, vec3 x, vec3 n);
// The same at `point` (x = point.p, n = point.basis.n).
std::array<double, 2> slc_child_weights(const LightNode& left, const LightNode& right, const ShadingPoint& point);
inline ChildWeights slc_weights(const ShadingPoint& point) {
  return [&point](const LightNode& l, const LightNode& r) { return slc_child_weights(l, r, point); };
}
inline bool stop_at_leaves(const LightNode& node) { return node.is_leaf(); }

// Builds the frame's tree in prepare: stage "tree_build", counters["tree"] = kind and stats.
class SlcSampler final : public TreeSamplerBase {
 public:
  explicit SlcSampler(LightTreeParams params) : TreeSamplerBase(std::move(params)) {}
  IndirectEstimate estimate(const ManyLightFrame& frame, const ShadingPoint& point, PixelSampler& sampler) const override;
  void gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const override;
};

}  // namespace sst
