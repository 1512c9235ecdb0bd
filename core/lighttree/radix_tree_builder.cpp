// The SST paper's builder (§3.3): the binary radix tree over the sorted keys (Karras 2012,
// "Maximizing parallelism in the construction of BVHs, octrees, and k-d trees"), merged bottom-up
// as the paper's GPU build does it: every leaf climbs towards the root; of a node's two children
// the first to arrive stops and the second merges the node and goes on. A node's value depends
// only on its children, not on which thread merged it, so the tree is the same for any thread
// count, and the same as the GPU's (light_tree_build_pass.cpp), node for node.
//
// The climbs find the topology as they go (Apetrei 2014; radix_tree_parent in radix_tree_node.h):
// a node's parent follows from the keys at the node's two ends, and the parent's other end from
// the child that arrived first, which left it in a meeting slot. So no pass computes Karras's node ranges
// and nothing stores them: that pass had taken a quarter of the build, and its parent links and
// ranges 24 bytes per VPL.
//
// On a CPU a task processes a whole chunk of consecutive leaves, in order. A parent wholly inside
// the chunk is reached first from its first child (whose leaves come first), so the arrivals need
// no ordering there; only parents that straddle chunk borders (a few per level) meet through an
// atomic exchange. A locked operation per node would serialise the memory accesses around it and
// stall every climb.
//
// The leaves are not stored (light_tree.h): a merge reads a leaf child as LightTree::node makes
// it, from its VPL.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

#include "core/lighttree/sort_key.h"
#include "core/lighttree/tree_builders.h"

#define RADIX_TREE_KEYS_PARAM const uint64_t* keys,
#define RADIX_TREE_KEYS_ARG keys,
#define RADIX_TREE_KEY(i) uvec2(uint32_t(keys[i]), uint32_t(keys[i] >> 32))
#include "core/lighttree/radix_tree_node.h"

namespace sst {
namespace {

constexpr int kPrefetch = 16;
constexpr uint32_t kMergeChunk = 2048;

}  // namespace

void build_radix_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, bool store_leaves,
                      LightTreeBuilder::Scratch& scratch, LightTree& tree) {
  const size_t n = tree.leaf_keys.size();
  set_leaf_source(vpls, thresholds, tree);
  resize_uninitialized(tree.nodes, n == 0 ? 0 : store_leaves ? 2 * n - 1 : n - 1, /*huge_pages=*/false);
  tree.stored_nodes = uint32_t(tree.nodes.size());
  tree.root = n == 0 ? kNoNode : 0;
  tree.first_leaf = n == 0 ? 0 : uint32_t(n - 1);
  tree.leaf_count = uint32_t(n);
  if (n == 0) return;
  if (n == 1) {  // a single leaf, the root
    if (store_leaves) write_leaves(tree, tree.nodes.data(), 0, 1);
    return;
  }
  // The meeting slots, one per split position: the far end of the child that arrived first,
  // plus one; 0 until then. They live in the sort's spare key buffer, which the keys no longer
  // need: 8 bytes a VPL that a buffer of their own would add to the peak memory.
  std::vector<uint64_t>& slots = scratch.sort.keys;
  if (slots.size() < n - 1) slots.resize(n - 1);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n - 1, 1 << 16), [&](const tbb::blocked_range<size_t>& r) {
    std::fill(slots.begin() + r.begin(), slots.begin() + r.end(), 0);
  });
  auto meet = [&](int split) { return std::atomic_ref<uint64_t>(slots[size_t(split)]); };
  LightNode* nodes = tree.nodes.data();
  const uint64_t* keys = tree.leaf_keys.data();
  const int count = int(n);
  // Chunks of at most kMergeChunk leaves: a chunk's internal nodes and VPLs then stay in the
  // core's cache while its climbs run.
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(n), kMergeChunk), [&](const tbb::blocked_range<uint32_t>& r) {
    const int chunk_begin = int(r.begin()), chunk_end = int(r.end());
    // Stored leaves first, as a loop of independent iterations: the VPLs are gathered in key
    // order, from scattered addresses, and the climbs below would stall on each of those loads.
    // A leaf of a neighbouring chunk is written before that chunk's climbs, hence before its
    // arrival at a parent that straddles the border.
    if (store_leaves) write_leaves(tree, tree.nodes.data(), uint32_t(chunk_begin), uint32_t(chunk_end));
    for (int i = chunk_begin; i != chunk_end; ++i) {
      // Made leaves' VPLs are read in key order too: fetch ahead of the climbs.
      if (!store_leaves && i + kPrefetch < chunk_end) __builtin_prefetch(&vpls[sort_key_vpl(keys[i + kPrefetch])]);
      int first = i, last = i;  // the node just completed
      RadixTreeParent up = radix_tree_parent(keys, count, first, last);  // unused at the root
      // That node once merged, kept for the next merge instead of read back from the array; a
      // leaf is made only when merged.
      LightNode done;
      while (first != 0 || last != count - 1) {
        const int split = int(up.split);
        // Whether the parent reaches past the chunk: a key there shares its prefix.
        const bool straddles =
            up.left_side
                ? first < chunk_begin || radix_tree_delta(keys, count, last, chunk_end) >= up.prefix
                : last >= chunk_end || radix_tree_delta(keys, count, first, chunk_begin - 1) >= up.prefix;
        const uint64_t own_end = uint64_t(up.left_side ? first : last) + 1;
        uint64_t other_end;
        if (!straddles) {
          if (up.left_side) {  // the second child's leaves come later in this loop
            meet(split).store(own_end, std::memory_order_relaxed);
            break;
          }
          other_end = meet(split).load(std::memory_order_relaxed);
        } else {
          // acq_rel makes the sibling's subtree visible to the second to arrive, and this
          // subtree to whoever arrives second above.
          other_end = meet(split).exchange(own_end, std::memory_order_acq_rel);
          if (other_end == 0) break;
        }
        const LightNode own = first == last ? tree.leaf(uint32_t(i)) : done;
        if (up.left_side)
          last = int(other_end) - 1;
        else
          first = int(other_end) - 1;
        const uint32_t left = radix_tree_index(count, first, split, true);
        const uint32_t right = radix_tree_index(count, split + 1, last, false);
        done = up.left_side ? merge_children(own, left, tree.node(right), right, thresholds)
                            : merge_children(tree.node(left), left, own, right, thresholds);
        up = radix_tree_parent(keys, count, first, last);  // the grandparent, for the next step
        nodes[radix_tree_index(count, first, last, up.left_side)] = done;
      }
    }
  }, tbb::simple_partitioner());
}

}  // namespace sst
