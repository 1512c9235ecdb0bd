// `slc`: stochastic lightcuts with one sample per cut (Yuksel 2019; docs/design/methods.md). Walks the
// light tree from the root to a leaf, choosing child i with probability w_i / (w_1 + w_2),
//   w_i = lum(I_i) * cosbound_i / dmin_i^2,
// cosbound = upper bound of the cosine at x (shading normal) over the child's box, dmin = the
// distance from x to the box. When x is within one box diagonal of either child (dmin_i <=
// diag_i), distance is ignored for both (w_i = lum(I_i) * cosbound_i): the 1/d^2 bound is
// meaningless there and would starve the sibling. Unbiased w.r.t. exhaustive: a weight is 0
// only when every VPL below contributes 0 (no intensity, or the box is behind the surface).
// The estimate is slc_estimate.h's; this is the method: its tree, and exact stop-node
// probabilities of the tree walks for tests.
#pragma once
#include <array>
#include <cmath>
#include <functional>

#include "core/lighttree/light_tree.h"
#include "core/manylight/indirect_sampler.h"
#include "core/manylight/slc/slc_estimate.h"
#include "core/manylight/tree_method_params.h"
#include "core/manylight/tree_sampler_base.h"

namespace sst {

// Child weights (w_left, w_right) of an internal node at a shading point, as the walks of
// slc_estimate.h and sst_estimate.h compute them: for exact stop probabilities in tests.
using ChildWeights = std::function<std::array<double, 2>(const LightNode& left, const LightNode& right)>;
// Whether the walk stops at this node (leaves always stop).
using StopRule = std::function<bool(const LightNode& node)>;

// The exact probability that a walk from tree.root with these weights stops at each node (indexed
// like tree.node(), [0, node_count()); 0 for nodes it never stops at). Sums to 1 over the nodes unless some branch is
// dead. For tests.
std::vector<double> stop_probabilities(const LightTree& tree, const ChildWeights& weights, const StopRule& stop);

// A walk down `tree` from the root with these weights, by tree_walk_step as the estimators walk,
// stopping at leaves and where `stop` says; its uniforms come from `ps`. For tests.
TreeWalk walk_tree(const LightTree& tree, const ChildWeights& weights, const StopRule& stop, PixelSampler& ps);
// A walk probability as a double.
inline double probability_value(TreeProbability p) { return std::ldexp(double(p.m), p.e); }

// slc_child_weights (slc_estimate.h) at `point` with node-distance floor `floor_fraction`.
inline ChildWeights slc_weights(const ShadingPoint& point, float floor_fraction = 0.0f) {
  return [&point, floor_fraction](const LightNode& l, const LightNode& r) -> std::array<double, 2> {
    vec2 w = slc_child_weights(l, r, point.p, point.basis, floor_fraction);
    return {w.x, w.y};
  };
}
inline bool stop_at_leaves(const LightNode& node) { return node.is_leaf(); }

// slc's parameters: the tree methods' (TreeMethodParams), with its own floor threshold.
struct SlcParams : TreeMethodParams {
  SlcParams() : TreeMethodParams(kNodeFloorAboveForSlc) {}
};

// Builds the frame's tree in prepare: stage "tree_build", counters["tree"] = kind and stats.
class SlcSampler final : public TreeSamplerBase {
 public:
  explicit SlcSampler(LightTreeParams params) : TreeSamplerBase(std::move(params)) {}
  IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const override {
    return estimate_slc(inputs(), point, sampler);
  }

 protected:
  uint32_t method_id() const override { return ML_METHOD_slc; }
};

}  // namespace sst
