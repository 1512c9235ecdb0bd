#version 450
#extension GL_GOOGLE_include_directive : require
// One level of the GPU perfect (heap) light tree, as core/lighttree/perfect_tree_builder.cpp
// merges it level by level above its subtrees. Parent first_leaf + i (a node of the level
// [first_leaf, 2 first_leaf)) is merge_children of nodes 2p and 2p + 1, the level below, written
// by the previous dispatch (light_tree_perfect_leaves.comp the level above the leaves). No loops and no atomics: every node depends only on its children, so
// the result is the CPU's whatever the scheduling.
//
// Dispatch: one per level, bottom-up (first_leaf = L/4, L/8, ..., 1), count = first_leaf
// invocations, ltb_index().
// Bindings: 0 LightNode nodes[]. Push: count (the level's width), first_leaf (its first node),
// v_min, sigma_max_abs.
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"
#include "core/lighttree/substitute.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) buffer Nodes { LightNode nodes[]; };

void main() {
  uint i = ltb_index();
  if (i >= ltb.count) return;
  SubstituteThresholds thresholds = SubstituteThresholds(ltb.v_min, ltb.sigma_max_abs);
  uint parent = ltb.first_leaf + i, left = 2u * parent, right = left + 1u;
  nodes[parent] = merge_children(nodes[left], left, nodes[right], right, thresholds);
}
