// The SST paper's builder (§3.3): a binary radix tree over the sorted keys (Karras 2012,
// "Maximizing parallelism in the construction of BVHs, octrees, and k-d trees"), then a
// bottom-up merge as the paper's GPU build does it: every leaf climbs towards the root; at each
// internal node an atomic counter lets the first arriving child stop and the second merge the
// node and go on. A node's value depends only on its children, not on which thread merged it,
// so the tree is the same for any thread count.
//
// On a CPU a task processes a whole chunk of consecutive leaves, in order, and every internal
// node covers a contiguous range of leaves. A node whose range lies inside the chunk is
// complete exactly when the climb from its last leaf reaches it, so it needs no counter; only
// nodes that straddle chunk borders (a few per level) use the atomic. A locked add per node
// would serialise the memory accesses around it and stall every climb.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/lighttree/sort_key.h"
#include "core/lighttree/tree_builders.h"

#define RADIX_TREE_KEYS_PARAM const uint64_t* keys,
#define RADIX_TREE_KEYS_ARG keys,
#define RADIX_TREE_KEY(i) uvec2(uint32_t(keys[i]), uint32_t(keys[i] >> 32))
#include "core/lighttree/radix_tree_node.h"

namespace sst {
namespace {

constexpr size_t kGrain = 1024;
constexpr uint32_t kPrefetch = 16;
constexpr uint32_t kMergeChunk = 2048;

}  // namespace

void build_radix_hierarchy(LightTreeBuilder::Scratch& scratch, LightTree& tree) {
  const size_t n = scratch.keys.size();
  resize_uninitialized(tree.nodes, n == 0 ? 0 : 2 * n - 1, /*huge_pages=*/false);
  tree.root = n == 0 ? kNoNode : 0;
  tree.first_leaf = n == 0 ? 0 : uint32_t(n - 1);
  tree.leaf_count = uint32_t(n);
  resize_uninitialized(scratch.parents, tree.nodes.size(), /*huge_pages=*/true);
  resize_uninitialized(scratch.topology, n == 0 ? 0 : n - 1, /*huge_pages=*/true);
  if (n == 0) return;
  scratch.parents[0] = kNoNode;
  const uint64_t* keys = scratch.keys.data();
  uint32_t* parents = scratch.parents.data();
  LightTreeBuilder::Scratch::Topology* topology = scratch.topology.data();
  tbb::parallel_for(tbb::blocked_range<int>(0, int(n) - 1, kGrain), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      RadixTreeNode node = radix_tree_node(keys, int(n), i);
      topology[i] = {node.left, node.right, node.first, node.last};
      parents[node.left] = uint32_t(i);
      parents[node.right] = uint32_t(i);
    }
  });
}

void merge_radix_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, LightTreeBuilder::Scratch& scratch,
                      LightTree& tree) {
  const size_t n = scratch.keys.size();
  if (n == 0) return;
  const size_t internal = n - 1;
  if (scratch.visits_size < internal) {
    scratch.visits = std::make_unique<std::atomic<uint32_t>[]>(internal);
    scratch.visits_size = internal;
  }
  std::atomic<uint32_t>* visits = scratch.visits.get();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, internal, 16 * kGrain), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) visits[i].store(0, std::memory_order_relaxed);
  });
  LightNode* nodes = tree.nodes.data();
  const uint32_t* parents = scratch.parents.data();
  const LightTreeBuilder::Scratch::Topology* topology = scratch.topology.data();
  const uint64_t* keys = scratch.keys.data();
  const uint32_t first_leaf = tree.first_leaf;
  // Chunks of at most kMergeChunk leaves: a chunk's leaves and internal nodes (2 x 96 bytes a
  // leaf) then stay in the core's cache between the leaf loop and the climbs.
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(n), kMergeChunk), [&](const tbb::blocked_range<uint32_t>& r) {
    const uint32_t chunk_begin = r.begin(), chunk_end = r.end();
    // Leaves first, as a loop of independent iterations: the VPLs are gathered in key order,
    // from scattered addresses, and the climbs below would stall on each of those loads.
    for (uint32_t i = chunk_begin; i != chunk_end; ++i) {
      if (i + kPrefetch < chunk_end) __builtin_prefetch(&vpls[sort_key_vpl(keys[i + kPrefetch])]);
      const uint32_t vpl = sort_key_vpl(keys[i]);
      nodes[first_leaf + i] = make_leaf(vpls[vpl], vpl, thresholds);
    }
    for (uint32_t i = chunk_begin; i != chunk_end; ++i) {
      for (uint32_t parent = parents[first_leaf + i]; parent != kNoNode; parent = parents[parent]) {
        const LightTreeBuilder::Scratch::Topology& t = topology[parent];
        const uint32_t lo = t.first, hi = t.last;
        if (lo >= chunk_begin && hi < chunk_end) {
          if (hi != i) break;  // inside the chunk: complete once its last leaf is done
        } else if (visits[parent].fetch_add(1, std::memory_order_acq_rel) == 0) {
          // Straddling: the first child to arrive stops. acq_rel makes the sibling's subtree
          // visible to the second, and this subtree to whoever arrives second above.
          break;
        }
        nodes[parent] = merge_children(nodes[t.left], t.left, nodes[t.right], t.right, thresholds);
      }
    }
  }, tbb::simple_partitioner());
}

}  // namespace sst
