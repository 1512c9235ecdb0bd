#include "core/manylight/slc/slc_sampler.h"

#include <cmath>

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

TreeWalk walk_tree(const LightTree& tree, const ChildWeights& weights, const StopRule& stop, PixelSampler& ps) {
  TreeWalk walk = tree_walk_begin(tree.empty() ? kNoNode : tree.root);
  while (walk.node != kNoNode) {
    walk.nodes_visited += 1u;
    const LightNode& node = tree[walk.node];
    if (node.is_leaf() || stop(node)) break;
    std::array<double, 2> w = weights(tree[node.left], tree[node.right]);
    tree_walk_step(walk, node, vec2(float(w[0]), float(w[1])), ps);
  }
  return walk;
}

std::vector<double> stop_probabilities(const LightTree& tree, const ChildWeights& weights, const StopRule& stop) {
  std::vector<double> out(tree.node_count(), 0.0);
  if (!tree.empty()) collect_stops(tree, weights, stop, tree.root, 1.0, out);
  return out;
}

}  // namespace sst
