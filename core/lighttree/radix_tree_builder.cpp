// The SST paper's builder (§3.3): the binary radix tree over the sorted keys (Karras 2012,
// "Maximizing parallelism in the construction of BVHs, octrees, and k-d trees"), merged bottom-up
// as the paper's GPU build does it: every leaf climbs towards the root; of a node's two children
// the first to arrive stops and the second merges the node and goes on. A node's value depends
// only on its children, not on which thread merged it, so the tree is the same for any thread
// count, and the same as the GPU's (light_tree_build_pass.cpp), node for node.
//
// The climbs find the topology as they go (Apetrei 2014; radix_tree_parent in radix_tree_node.h):
// a node's parent follows from the keys at the node's two ends, and the parent's other end from
// the child that arrived first, which left it in `meets`. So no pass computes Karras's node ranges
// and nothing stores them: that pass had taken a quarter of the build, and its parent links and
// ranges 24 bytes per VPL.
//
// On a CPU a task processes a whole chunk of consecutive leaves, in order. A parent wholly inside
// the chunk is reached first from its first child (whose leaves come first), so the arrivals need
// no atomic there; only parents that straddle chunk borders (a few per level) meet through an
// atomic exchange. A locked operation per node would serialise the memory accesses around it and
// stall every climb.
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

constexpr int kPrefetch = 16;
constexpr uint32_t kMergeChunk = 2048;

}  // namespace

void build_radix_tree(const VplSet& vpls, const SubstituteThresholds& thresholds, LightTreeBuilder::Scratch& scratch,
                      LightTree& tree) {
  const size_t n = scratch.keys.size();
  resize_uninitialized(tree.nodes, n == 0 ? 0 : 2 * n - 1, /*huge_pages=*/false);
  tree.root = n == 0 ? kNoNode : 0;
  tree.first_leaf = n == 0 ? 0 : uint32_t(n - 1);
  tree.leaf_count = uint32_t(n);
  if (n == 0) return;
  const size_t internal = n - 1;
  if (scratch.meets.size() < internal) {
    scratch.meets = std::vector<std::atomic<uint32_t>>(internal);  // zeroed
  } else if (!scratch.meets_clean) {
    for (std::atomic<uint32_t>& m : scratch.meets) m.store(0, std::memory_order_relaxed);
  }
  scratch.meets_clean = false;
  std::atomic<uint32_t>* meets = scratch.meets.data();
  LightNode* nodes = tree.nodes.data();
  const uint64_t* keys = scratch.keys.data();
  const int count = int(n);
  const uint32_t first_leaf = tree.first_leaf;
  // Chunks of at most kMergeChunk leaves: a chunk's leaves and internal nodes (2 x 96 bytes a
  // leaf) then stay in the core's cache between the leaf loop and the climbs.
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(n), kMergeChunk), [&](const tbb::blocked_range<uint32_t>& r) {
    const int chunk_begin = int(r.begin()), chunk_end = int(r.end());
    // Leaves first, as a loop of independent iterations: the VPLs are gathered in key order,
    // from scattered addresses, and the climbs below would stall on each of those loads.
    for (int i = chunk_begin; i != chunk_end; ++i) {
      if (i + kPrefetch < chunk_end) __builtin_prefetch(&vpls[sort_key_vpl(keys[i + kPrefetch])]);
      const uint32_t vpl = sort_key_vpl(keys[i]);
      nodes[first_leaf + uint32_t(i)] = make_leaf(vpls[vpl], vpl, thresholds);
    }
    for (int i = chunk_begin; i != chunk_end; ++i) {
      int first = i, last = i;  // the node just completed
      RadixTreeParent up = radix_tree_parent(keys, count, first, last);  // unused at the root
      while (first != 0 || last != count - 1) {
        const int split = int(up.split);
        // Whether the parent reaches past the chunk: a key there shares its prefix.
        const bool straddles =
            up.left_side
                ? first < chunk_begin || radix_tree_delta(keys, count, last, chunk_end) >= up.prefix
                : last >= chunk_end || radix_tree_delta(keys, count, first, chunk_begin - 1) >= up.prefix;
        const uint32_t own_end = uint32_t(up.left_side ? first : last) + 1;
        uint32_t other_end;
        if (!straddles) {
          if (up.left_side) {  // the second child's leaves come later in this loop
            meets[split].store(own_end, std::memory_order_relaxed);
            break;
          }
          other_end = meets[split].load(std::memory_order_relaxed);
        } else {
          // acq_rel makes the sibling's subtree visible to the second to arrive, and this
          // subtree to whoever arrives second above.
          other_end = meets[split].exchange(own_end, std::memory_order_acq_rel);
          if (other_end == 0) break;
        }
        meets[split].store(0, std::memory_order_relaxed);  // ready for the next build
        if (up.left_side)
          last = int(other_end) - 1;
        else
          first = int(other_end) - 1;
        const uint32_t left = radix_tree_index(count, first, split, true);
        const uint32_t right = radix_tree_index(count, split + 1, last, false);
        up = radix_tree_parent(keys, count, first, last);  // the grandparent, for the next step
        const uint32_t parent = radix_tree_index(count, first, last, up.left_side);
        nodes[parent] = merge_children(nodes[left], left, nodes[right], right, thresholds);
      }
    }
  }, tbb::simple_partitioner());
  scratch.meets_clean = true;
}

}  // namespace sst
