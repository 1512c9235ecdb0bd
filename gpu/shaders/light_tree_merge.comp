#version 450
#extension GL_GOOGLE_include_directive : require
// The radix tree found and merged bottom-up, as core/lighttree/radix_tree_builder.cpp's
// build_radix_tree does it (Apetrei 2014; the topology from radix_tree_node.h's
// radix_tree_parent and radix_tree_index): one invocation per sorted position i climbs from
// leaf first_leaf + i, which the GPU does not store: light_tree_node makes it from VPL ids[i],
// as for LightTree::node (the host stores the leaves, store_leaves, where asked to). At each parent
// the child that arrives first leaves its far end in meets[split] and stops; the second takes
// it, which completes the parent's range, and merges the parent (merge_children,
// core/lighttree/substitute.h). Which child is left is the node's, not the arrival order's, so
// the tree does not depend on scheduling. A climb is at most 64 nodes long (the radix tree's
// height is bounded by the key's 64 bits).
//
// Dispatch: one workgroup per VPL (x, y with x <= 65535), ltb_group() is the sorted position.
// Bindings: 0 GpuVpl vpls[], 1 uint ids[] (sorted), 2 uvec2 keys[] (sorted, unique), 3 uint
// meets[] (count - 1, zeroed by the host), 4 LightNode nodes[] (count - 1). Push: count (VPLs),
// first_leaf, v_min, sigma_max_abs.
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"

// One invocation per workgroup: lavapipe (llvmpipe, LLVM 15) runs a workgroup's invocations as
// SIMD lanes and mis-executes the branch on an atomic's result when lanes diverge in the climb
// (the second arrival skipped its merge, leaving nodes unwritten); alone in its group an
// invocation has no lanes to diverge from. Costs ~3x the merge time on lavapipe.
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = 1) readonly buffer Ids { uint ids[]; };
layout(std430, binding = 2) readonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = 3) coherent buffer Meets { uint meets[]; };
layout(std430, binding = 4) coherent buffer Nodes { LightNode nodes[]; };

#define RADIX_TREE_KEY(i) keys[i]
#include "core/lighttree/radix_tree_node.h"
#define LIGHT_TREE_STORED(i) nodes[i]
#define LIGHT_TREE_LEAF_VPL(j) ids[j]
#define LIGHT_TREE_VPL(v) vpls[v]
#include "core/lighttree/light_tree_node.h"

void main() {
  uint i = ltb_group();
  if (i >= ltb.count) return;
  SubstituteThresholds thresholds = SubstituteThresholds(ltb.v_min, ltb.sigma_max_abs);
  int n = int(ltb.count);
  int first = int(i);
  int last = int(i);
  RadixTreeParent up = radix_tree_parent(n, first, last);  // unused at the root
  while (first != 0 || last != n - 1) {
    // Publish this subtree before arriving; the second arrival sees both children.
    memoryBarrierBuffer();
    uint other_end = atomicExchange(meets[up.split], uint(up.left_side ? first : last) + 1u);
    if (other_end == 0u) return;
    memoryBarrierBuffer();
    int split = int(up.split);
    if (up.left_side)
      last = int(other_end) - 1;
    else
      first = int(other_end) - 1;
    uint left = radix_tree_index(n, first, split, true);
    uint right = radix_tree_index(n, split + 1, last, false);
    up = radix_tree_parent(n, first, last);
    uint parent = radix_tree_index(n, first, last, up.left_side);
    LightNode a = light_tree_node(left, ltb.first_leaf, ltb.first_leaf, ltb.count, thresholds);
    LightNode b = light_tree_node(right, ltb.first_leaf, ltb.first_leaf, ltb.count, thresholds);
    nodes[parent] = merge_children(a, left, b, right, thresholds);
  }
}
