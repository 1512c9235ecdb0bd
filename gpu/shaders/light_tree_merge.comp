#version 450
#extension GL_GOOGLE_include_directive : require
// The bottom-up merge of the GPU light-tree build, as the SST paper's GPU build does it and as
// core/lighttree/radix_tree_builder.cpp's merge_radix_tree does across its chunks: one invocation
// per sorted position i writes leaf first_leaf + i (make_leaf of VPL ids[i]) and climbs; at each
// internal node an atomic counter stops the first child to arrive, the second merges the node
// (merge_children, core/lighttree/substitute.h) and goes on. Which child is left is the node's,
// not the arrival order's, so the tree does not depend on scheduling. A climb is at most 64
// nodes long (the radix tree's height is bounded by the key's 64 bits).
//
// Dispatch: one workgroup per VPL (x, y with x <= 65535), ltb_group() is the sorted position.
// Bindings: 0 GpuVpl vpls[], 1 uint ids[] (sorted), 2 uint parents[], 3 uint visits[] (zeroed by
// the hierarchy pass), 4 LightNode nodes[]. Push: count (VPLs), first_leaf, v_min, sigma_max_abs.
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"
#include "core/lighttree/substitute.h"

// One invocation per workgroup: lavapipe (llvmpipe, LLVM 15) runs a workgroup's invocations as
// SIMD lanes and mis-executes the branch on atomicAdd's result when lanes diverge in the climb
// (the second arrival skipped its merge, leaving nodes unwritten); alone in its group an
// invocation has no lanes to diverge from. Costs ~3x the merge time on lavapipe.
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = 1) readonly buffer Ids { uint ids[]; };
layout(std430, binding = 2) readonly buffer Parents { uint parents[]; };
layout(std430, binding = 3) coherent buffer Visits { uint visits[]; };
layout(std430, binding = 4) coherent buffer Nodes { LightNode nodes[]; };

void main() {
  uint i = ltb_group();
  if (i >= ltb.count) return;
  SubstituteThresholds thresholds = SubstituteThresholds(ltb.v_min, ltb.sigma_max_abs);
  uint vpl = ids[i];
  uint node = ltb.first_leaf + i;
  nodes[node] = make_leaf(vpls[vpl].position, vpls[vpl].normal, vpls[vpl].intensity, vpl, thresholds);
  for (uint parent = parents[node]; parent != kNoNode; parent = parents[parent]) {
    // Publish this subtree before arriving; the second arrival sees both children.
    memoryBarrierBuffer();
    if (atomicAdd(visits[parent], 1u) == 0u) return;
    memoryBarrierBuffer();
    uint left = nodes[parent].left, right = nodes[parent].right;
    nodes[parent] = merge_children(nodes[left], left, nodes[right], right, thresholds);
  }
}
