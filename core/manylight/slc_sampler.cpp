#include "core/manylight/slc_sampler.h"

#include <cmath>

#include "core/lighttree/box_bounds.h"
#include "core/manylight/exhaustive_sampler.h"
#include "core/manylight/gpu_sampler_inputs.h"

namespace sst {
namespace {

void collect_stops(const LightTree& tree, const ChildWeights& weights, const StopRule& stop, uint32_t i, double p,
                   std::vector<double>& out) {
  const LightNode& node = tree[i];
  if (node.is_leaf() || stop(node)) {
    out[i] += p;
    return;
  }
  std::array<double, 2> w = weights(tree[node.left], tree[node.right]);
  double sum = w[0] + w[1];
  if (!(sum > 0.0) || !std::isfinite(sum)) return;  // dead branch: its mass is lost
  if (w[0] > 0.0) collect_stops(tree, weights, stop, node.left, p * (w[0] / sum), out);
  if (w[1] > 0.0) collect_stops(tree, weights, stop, node.right, p * (w[1] / sum), out);
}

}  // namespace

TreeTraversal traverse_tree(const LightTree& tree, const ChildWeights& weights, const StopRule& stop,
                            const std::function<float()>& u) {
  TreeTraversal t;
  if (tree.empty()) return t;
  uint32_t i = tree.root;
  double p = 1.0;
  for (;;) {
    ++t.nodes_visited;
    const LightNode& node = tree[i];
    if (node.is_leaf() || stop(node)) break;
    std::array<double, 2> w = weights(tree[node.left], tree[node.right]);
    double sum = w[0] + w[1];
    if (!(sum > 0.0) || !std::isfinite(sum)) return t;  // dead branch: the sample is wasted
    double p_left = w[0] / sum;
    // A child of weight 0 is never taken, whatever u: its VPLs contribute nothing.
    bool left = w[1] <= 0.0 || (w[0] > 0.0 && double(u()) < p_left);
    p *= left ? p_left : w[1] / sum;
    i = left ? node.left : node.right;
  }
  t.node = i;
  t.probability = p;
  return t;
}

vec3 divide_by_probability(vec3 c, double p) {
  if (!(p > 0.0) || max_component(c) <= 0.0f) return vec3(0.0f);
  // In double: P of a deep path can be far below float's range while c / P is moderate.
  vec3 v(float(double(c.x) / p), float(double(c.y) / p), float(double(c.z) / p));
  return is_finite(v) ? v : vec3(0.0f);
}

std::vector<double> stop_probabilities(const LightTree& tree, const ChildWeights& weights, const StopRule& stop) {
  std::vector<double> out(tree.nodes.size(), 0.0);
  if (!tree.empty()) collect_stops(tree, weights, stop, tree.root, 1.0, out);
  return out;
}

std::array<double, 2> slc_child_weights(const LightNode& left, const LightNode& right, vec3 x, vec3 n) {
  const LightNode* c[2] = {&left, &right};
  double base[2], d2[2];
  bool near = false;
  for (int k = 0; k < 2; ++k) {
    const LightNode& node = *c[k];
    base[k] = node.empty() ? 0.0 : double(luminance(node.intensity)) * box_cos_bound(node.bounds(), x, n);
    d2[k] = node.empty() ? 0.0 : box_distance2_min(node.bounds(), x);
    float diag = node.bounds().diagonal();
    // <= rather than <: a point box (diag 0) at x itself must not divide by 0.
    if (!node.empty() && d2[k] <= double(diag) * double(diag)) near = true;
  }
  if (near) return {base[0], base[1]};
  return {base[0] > 0.0 ? base[0] / d2[0] : 0.0, base[1] > 0.0 ? base[1] / d2[1] : 0.0};
}

std::array<double, 2> slc_child_weights(const LightNode& left, const LightNode& right, const ShadingPoint& point) {
  return slc_child_weights(left, right, point.p, point.basis.n);
}

IndirectEstimate SlcSampler::estimate(const ManyLightFrame& frame, const ShadingPoint& point,
                                      PixelSampler& sampler) const {
  IndirectEstimate e;
  TreeTraversal t = traverse_tree(tree_, slc_weights(point), stop_at_leaves, [&] { return pixel_sampler_get1d(sampler); });
  e.nodes_visited = t.nodes_visited;
  if (t.node == kNoNode || !(t.probability > 0.0)) return e;
  uint32_t vpl = tree_[t.node].vpl();
  if (vpl == kNoNode || vpl >= frame.vpls.size()) return e;  // a padding leaf (never drawn: weight 0)
  e.value = divide_by_probability(shade_vpl(frame, point, frame.vpls[vpl], &e.shadow_rays), t.probability);
  return e;
}

void SlcSampler::gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const {
  begin_gpu_inputs(frame, ML_METHOD_SLC, out);
  set_tree_inputs(tree_, out);
}

}  // namespace sst
