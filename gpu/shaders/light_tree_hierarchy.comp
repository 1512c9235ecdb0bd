#version 450
#extension GL_GOOGLE_include_directive : require
// The radix tree over the sorted keys (core/lighttree/radix_tree_node.h), one invocation per
// internal node i: writes node i's children into nodes[i].left/right (the merge writes the
// rest), the parents of both children, and zeroes the merge's arrival counter of i.
//
// Bindings: 0 uvec2 keys[] (sorted, unique), 1 LightNode nodes[], 2 uint parents[],
// 3 uint visits[]. Push: count (internal nodes, VPLs - 1).
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = 1) buffer Nodes { LightNode nodes[]; };
layout(std430, binding = 2) writeonly buffer Parents { uint parents[]; };
layout(std430, binding = 3) writeonly buffer Visits { uint visits[]; };

#define RADIX_TREE_KEY(i) keys[i]
#include "core/lighttree/radix_tree_node.h"

void main() {
  uint i = ltb_index();
  if (i >= ltb.count) return;
  RadixTreeNode node = radix_tree_node(int(ltb.count) + 1, int(i));
  nodes[i].left = node.left;
  nodes[i].right = node.right;
  parents[node.left] = i;
  parents[node.right] = i;
  visits[i] = 0u;
}
