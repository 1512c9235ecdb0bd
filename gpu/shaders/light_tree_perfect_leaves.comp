#version 450
#extension GL_GOOGLE_include_directive : require
// The level above the leaves of the GPU perfect (heap) light tree, laid out as build_perfect_tree
// (core/lighttree/perfect_tree_builder.cpp) lays it out, made by core/lighttree/substitute.h.
// The GPU does not store the leaves (the host does, store_leaves, where asked to): leaf position j
// is light_tree_leaf's, make_leaf of VPL ids[j] for j < count and a padding leaf past it
// (core/lighttree/light_tree_node.h). Invocation i < L/2 merges leaves 2i and 2i + 1 into node
// L/2 + i; invocation 0 also writes node 0, the unused padding leaf that keeps the heap's indices
// 1-based.
//
// Dispatch: max(L/2, 1) invocations (L, the power of two >= count), ltb_index().
// Bindings: 0 GpuVpl vpls[], 1 uint ids[] (sorted), 2 LightNode nodes[] (L). Push: count (VPLs),
// first_leaf (L), v_min, sigma_max_abs.
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = 1) readonly buffer Ids { uint ids[]; };
layout(std430, binding = 2) buffer Nodes { LightNode nodes[]; };  // light_tree_node.h reads it too

#define LIGHT_TREE_STORED(i) nodes[i]
#define LIGHT_TREE_LEAF_VPL(j) ids[j]
#define LIGHT_TREE_VPL(v) vpls[v]
#include "core/lighttree/light_tree_node.h"

void main() {
  uint i = ltb_index();
  SubstituteThresholds thresholds = SubstituteThresholds(ltb.v_min, ltb.sigma_max_abs);
  if (i == 0u) nodes[0] = make_padding_leaf(thresholds);
  uint parents = ltb.first_leaf / 2u;
  if (i >= parents) return;
  uint parent = parents + i, left = 2u * parent, right = left + 1u;
  LightNode a = light_tree_leaf(2u * i, ltb.count, thresholds);
  LightNode b = light_tree_leaf(2u * i + 1u, ltb.count, thresholds);
  nodes[parent] = merge_children(a, left, b, right, thresholds);
}
