// The builders behind build_light_tree(), for light_tree.cpp and the benchmark. Each fills
// `tree.nodes` (the internal nodes, and the leaves after them with `store_leaves`),
// `stored_nodes`, `leaf_keys`, `root`, `first_leaf` and `leaf_count`;
// light_tree.cpp does the rest (bounds, thresholds, VPLs, parameter checks) and times the stages.
#pragma once
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/math/radix_sort.h"
#include "core/lighttree/substitute.h"

namespace sst {

struct LightTreeBuilder::Scratch {
  RadixSortScratch sort;  // radix: its spare key buffer holds the climbs' meeting slots after the sort
};

// What LightTree::node() makes the leaves from: the VPLs and the thresholds of their flags. Every
// builder sets it first, so that its merges can read the leaves too.
inline void set_leaf_source(const VplSet& vpls, const SubstituteThresholds& thresholds, LightTree& tree) {
  tree.vpls = vpls;
  tree.vpl_count = uint32_t(vpls.size());
  tree.v_min = thresholds.v_min;
  tree.sigma_max_abs = thresholds.sigma_max_abs;
}

// Writes leaf positions [begin, end) of `tree` into nodes[first_leaf + begin, first_leaf + end),
// as node() makes them: tree.nodes.data() to store them (leaves = stored), or a copy's array.
inline void write_leaves(const LightTree& tree, LightNode* nodes, uint32_t begin, uint32_t end) {
  constexpr uint32_t kAhead = 16;
  for (uint32_t j = begin; j != end; ++j) {
    // The VPLs are gathered in key order, from scattered addresses: fetch ahead.
    if (j + kAhead < tree.vpl_count) __builtin_prefetch(&tree.vpls[sort_key_vpl(tree.leaf_keys[j + kAhead])]);
    nodes[tree.first_leaf + j] = tree.leaf(j);
  }
}

// Keys of `vpls` over `vpl_bounds`, sorted into tree.leaf_keys. Times the two stages into `stats`.
void sort_vpls(const VplSet& vpls, const Bounds3& vpl_bounds, LightTreeBuilder::Scratch& scratch, LightTree& tree,
               LightTreeBuildStats& stats);

// The radix tree of Karras 2012 over tree.leaf_keys (needs sort_vpls first), found and merged in
// one bottom-up pass (Apetrei 2014).
void build_radix_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, bool store_leaves,
                      LightTreeBuilder::Scratch& scratch, LightTree& tree);

// Heap layout over the sorted VPLs (needs sort_vpls first), merged level by level.
void build_perfect_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, bool store_leaves, LightTree& tree);

// Walter 2005 greedy pairing; O(n^2) time, so limited to kMaxAgglomerativeVpls.
inline constexpr size_t kMaxAgglomerativeVpls = 20000;
void build_agglomerative_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, float length_scale,
                              bool store_leaves, LightTree& tree);

}  // namespace sst
