// The perfect binary tree of RTSLC (Lin & Yuksel 2020) and the hybrid thesis (§4.2.2): the
// sorted VPLs are the leaves of a complete heap, padded to a power of two with empty leaves, and
// there is no topology to build: node i's children are 2i and 2i+1. Merged bottom-up; every
// node depends only on its children, so the result does not depend on the thread count.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>

#include "core/lighttree/sort_key.h"
#include "core/lighttree/tree_builders.h"

namespace sst {
namespace {

constexpr size_t kGrain = 1024;
constexpr uint32_t kPrefetch = 8;
// Leaves of one task's subtree: its nodes stay in the core's cache from the leaves up to the
// subtree's root, where a level-by-level pass over the whole array would stream it through
// memory once per level.
constexpr uint32_t kSubtreeLeaves = 2048;

void merge_range(uint32_t begin, uint32_t end, const SubstituteThresholds& thresholds, LightTree& tree) {
  const bool above_made_leaves = 2 * begin >= tree.first_leaf && tree.stored_nodes == tree.first_leaf;
  for (uint32_t i = begin; i != end; ++i) {
    // Above made leaves the VPLs are read in key order, from scattered addresses: fetch ahead.
    const uint32_t ahead = 2 * (i + kPrefetch) - tree.first_leaf;
    if (above_made_leaves && i + kPrefetch < end && ahead + 1 < tree.vpl_count) {
      __builtin_prefetch(&tree.vpls[sort_key_vpl(tree.leaf_keys[ahead])]);
      __builtin_prefetch(&tree.vpls[sort_key_vpl(tree.leaf_keys[ahead + 1])]);
    }
    tree.nodes[i] = merge_children(tree.node(2 * i), 2 * i, tree.node(2 * i + 1), 2 * i + 1, thresholds);
  }
}

}  // namespace

void build_perfect_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, bool store_leaves, LightTree& tree) {
  const size_t n = tree.leaf_keys.size();
  set_leaf_source(vpls, thresholds, tree);
  if (n == 0) {
    tree.nodes.clear();
    tree.stored_nodes = 0;
    tree.root = kNoNode;
    tree.first_leaf = tree.leaf_count = 0;
    return;
  }
  const uint32_t leaves = std::bit_ceil(uint32_t(n));
  resize_uninitialized(tree.nodes, store_leaves ? 2 * size_t(leaves) : leaves, /*huge_pages=*/false);
  tree.stored_nodes = uint32_t(tree.nodes.size());
  tree.root = 1;
  tree.first_leaf = leaves;
  tree.leaf_count = leaves;
  tree.nodes[0] = make_padding_leaf(thresholds);  // unused: keeps the heap's 1-based indices
  // Subtrees of `sub` leaves in parallel, each from its leaves up to its root (subtree k's
  // nodes of one level are consecutive: [(leaves + k sub) / 2^l, + sub / 2^l)) ...
  const uint32_t sub = std::min(leaves, kSubtreeLeaves), subtrees = leaves / sub;
  tbb::parallel_for(uint32_t(0), subtrees, [&](uint32_t k) {
    if (store_leaves) write_leaves(tree, tree.nodes.data(), k * sub, (k + 1) * sub);  // before the merges read them
    for (uint32_t first = (leaves + k * sub) / 2, width = sub / 2; width >= 1; first /= 2, width /= 2)
      merge_range(first, first + width, thresholds, tree);
  });
  // ... then the few levels above them, [1, subtrees), level by level.
  for (uint32_t level = subtrees / 2; level >= 1; level /= 2) {
    tbb::parallel_for(tbb::blocked_range<uint32_t>(level, 2 * level, kGrain),
                      [&](const tbb::blocked_range<uint32_t>& r) { merge_range(r.begin(), r.end(), thresholds, tree); });
  }
}

}  // namespace sst
