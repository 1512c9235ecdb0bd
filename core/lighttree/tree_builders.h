// The builders behind build_light_tree(), for light_tree.cpp and the benchmark. Each fills
// `tree.nodes`, `root`, `first_leaf` and `leaf_count`; light_tree.cpp does the rest (bounds,
// thresholds, parameter checks) and times the stages.
#pragma once
#include <atomic>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/math/radix_sort.h"
#include "core/lighttree/substitute.h"

namespace sst {

struct LightTreeBuilder::Scratch {
  std::vector<uint64_t> keys;  // after sorting: ascending; sort_key_vpl(keys[i]) is the VPL at position i
  RadixSortScratch sort;
  // radix: per split position (internal node), the far end of the child that reached it first,
  // plus one; 0 until then. All 0 after a build: each second arrival clears its slot. A build cut
  // short (an exception) leaves meets_clean false, and the next build clears them all first.
  std::vector<std::atomic<uint32_t>> meets;
  bool meets_clean = true;
};

// Keys of `vpls` over `vpl_bounds`, sorted into scratch.keys. Times the two stages into `stats`.
void sort_vpls(const VplSet& vpls, const Bounds3& vpl_bounds, LightTreeBuilder::Scratch& scratch,
               LightTreeBuildStats& stats);

// The radix tree of Karras 2012 over the sorted keys (needs sort_vpls first), found and merged in
// one bottom-up pass (Apetrei 2014).
void build_radix_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, LightTreeBuilder::Scratch& scratch,
                      LightTree& tree);

// Heap layout over the sorted VPLs (needs sort_vpls first), merged level by level.
void build_perfect_tree(const VplSet& vpls, const SubstituteThresholds& thresholds,
                        const LightTreeBuilder::Scratch& scratch, LightTree& tree);

// Walter 2005 greedy pairing; O(n^2) time, so limited to kMaxAgglomerativeVpls.
inline constexpr size_t kMaxAgglomerativeVpls = 20000;
void build_agglomerative_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, float length_scale,
                              LightTree& tree);

}  // namespace sst
