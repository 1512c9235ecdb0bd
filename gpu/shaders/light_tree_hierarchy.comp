#version 450
#extension GL_GOOGLE_include_directive : require
// Karras 2012's radix tree over the sorted keys, one invocation per internal node: the GLSL twin
// of build_internal_node in core/lighttree/radix_tree_builder.cpp, the same searches in the same
// order, so the same children. Writes node i's children into nodes[i].left/right (the merge
// writes the rest), the parents of both children, and zeroes the merge's arrival counter of i.
// Loops are short: at most 2 x 64 steps (keys have 64 bits).
//
// Bindings: 0 uvec2 keys[] (sorted, unique), 1 LightNode nodes[], 2 uint parents[],
// 3 uint visits[]. Push: count (internal nodes, VPLs - 1), first_leaf (= count).
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = 1) buffer Nodes { LightNode nodes[]; };
layout(std430, binding = 2) writeonly buffer Parents { uint parents[]; };
layout(std430, binding = 3) writeonly buffer Visits { uint visits[]; };

// Length of the longest common prefix of keys i and j; -1 when j is outside [0, n). Keys are
// unique, so the xor is never 0.
int delta(int i, int j) {
  int n = int(ltb.count) + 1;
  if (j < 0 || j >= n) return -1;
  uvec2 x = keys[i] ^ keys[j];
  return x.y != 0u ? 31 - findMSB(x.y) : 63 - findMSB(x.x);
}

void main() {
  uint index = ltb_index();
  if (index >= ltb.count) return;
  int i = int(index);
  int d = delta(i, i + 1) - delta(i, i - 1) >= 0 ? 1 : -1;
  int prefix_min = delta(i, i - d);
  int length_max = 2;
  while (delta(i, i + length_max * d) > prefix_min) length_max *= 2;
  int len = 0;
  for (int t = length_max / 2; t >= 1; t /= 2)
    if (delta(i, i + (len + t) * d) > prefix_min) len += t;
  int j = i + len * d;
  int prefix_node = delta(i, j);
  int split = 0;
  for (int t = len;;) {
    t = (t + 1) / 2;
    if (delta(i, i + (split + t) * d) > prefix_node) split += t;
    if (t <= 1) break;
  }
  int gamma = i + split * d + min(d, 0);
  uint first_leaf = ltb.first_leaf;
  uint left = min(i, j) == gamma ? first_leaf + uint(gamma) : uint(gamma);
  uint right = max(i, j) == gamma + 1 ? first_leaf + uint(gamma + 1) : uint(gamma + 1);
  nodes[i].left = left;
  nodes[i].right = right;
  parents[left] = uint(i);
  parents[right] = uint(i);
  visits[i] = 0u;
}
