// The binary radix tree over sorted, unique keys (Karras 2012, "Maximizing parallelism in the
// construction of BVHs, octrees, and k-d trees", Figure 4): the SST paper's light-tree topology
// (§3.3), in shared C++/GLSL source (core/math/cpu_gpu.h). Every node's children and the range of
// sorted leaves it covers depend only on the keys. radix_tree_node computes one internal node
// top-down, as Karras numbers them: the definition the tests hold the builders to. Both backends'
// builders find the same nodes bottom-up instead, while they merge (radix_tree_parent and
// radix_tree_index below).
//
// Node layout of n keys: internal nodes [0, n-1), root 0; leaf k is node n-1+k.
//
// Convention for the including file, C++ or GLSL, before the #include:
//   RADIX_TREE_KEY(i)       an expression of type uvec2: sorted key i (x = bits 0..31, y = bits
//                           32..63; GLSL: `keys[i]` of an SSBO)
//   RADIX_TREE_KEYS_PARAM   optional: a leading parameter of the functions below, with its
//                           trailing comma, through which RADIX_TREE_KEY reaches the keys (C++:
//                           `const uint64_t* keys,`); empty by default (GLSL buffers are globals)
//   RADIX_TREE_KEYS_ARG     with RADIX_TREE_KEYS_PARAM: the same parameter as an argument
// Loops are short: at most 2 x 64 steps (keys have 64 bits).
#ifndef SST_CORE_LIGHTTREE_RADIX_TREE_NODE_H
#define SST_CORE_LIGHTTREE_RADIX_TREE_NODE_H
#include "core/math/cpu_gpu.h"

#ifndef RADIX_TREE_KEY
#error "define RADIX_TREE_KEY(i) before including radix_tree_node.h"
#endif
#ifndef RADIX_TREE_KEYS_PARAM
#define RADIX_TREE_KEYS_PARAM
#endif
#ifndef RADIX_TREE_KEYS_ARG
#define RADIX_TREE_KEYS_ARG
#endif

SST_BEGIN

struct RadixTreeNode {
  uint left;   // first child's node index
  uint right;  // second child's node index
  uint first;  // the node's leaves are the sorted positions [first, last]
  uint last;
};

// Length of the longest common prefix of two 64-bit keys held as (low, high) words.
SST_FUNC int key_common_prefix(uvec2 a, uvec2 b) {
  uint lo = a.x ^ b.x;
  uint hi = a.y ^ b.y;
  return hi != 0u ? 31 - findMSB(hi) : 63 - findMSB(lo);
}

// The common prefix of keys i and j of n; -1 when j is outside [0, n). Keys are unique (they end
// in the VPL id), so it is at most 63.
SST_FUNC int radix_tree_delta(RADIX_TREE_KEYS_PARAM int n, int i, int j) {
  if (j < 0 || j >= n) return -1;
  return key_common_prefix(RADIX_TREE_KEY(i), RADIX_TREE_KEY(j));
}

// Internal node i (< n - 1) of the radix tree over n keys.
SST_FUNC RadixTreeNode radix_tree_node(RADIX_TREE_KEYS_PARAM int n, int i) {
  // Direction of the node's key range: towards the neighbour sharing the longer prefix.
  int d = radix_tree_delta(RADIX_TREE_KEYS_ARG n, i, i + 1) - radix_tree_delta(RADIX_TREE_KEYS_ARG n, i, i - 1) >= 0
              ? 1
              : -1;
  // Upper bound of the range's length, then its exact other end j by binary search.
  int prefix_min = radix_tree_delta(RADIX_TREE_KEYS_ARG n, i, i - d);
  int length_max = 2;
  while (radix_tree_delta(RADIX_TREE_KEYS_ARG n, i, i + length_max * d) > prefix_min) length_max *= 2;
  // The searches' comparisons are coin flips for a branch predictor: add by mask instead.
  int len = 0;
  for (int t = length_max / 2; t >= 1; t /= 2)
    len += t & -int(radix_tree_delta(RADIX_TREE_KEYS_ARG n, i, i + (len + t) * d) > prefix_min);
  int j = i + len * d;
  // The split: the last position that shares more than the range's common prefix with i.
  int prefix_node = radix_tree_delta(RADIX_TREE_KEYS_ARG n, i, j);
  int split = 0;
  for (int t = len;;) {
    t = (t + 1) / 2;
    split += t & -int(radix_tree_delta(RADIX_TREE_KEYS_ARG n, i, i + (split + t) * d) > prefix_node);
    if (t <= 1) break;
  }
  int gamma = i + split * d + min(d, 0);
  uint first_leaf = uint(n - 1);
  RadixTreeNode node;
  node.left = min(i, j) == gamma ? first_leaf + uint(gamma) : uint(gamma);
  node.right = max(i, j) == gamma + 1 ? first_leaf + uint(gamma + 1) : uint(gamma + 1);
  node.first = uint(min(i, j));
  node.last = uint(max(i, j));
  return node;
}

// The same tree found bottom-up (Apetrei 2014, "Fast and Simple Agglomerative LBVH
// Construction"): the node covering sorted positions [first, last] knows its parent from the keys
// at its two ends alone, which lets a climb from the leaves merge as it goes, with no topology
// stored. A node's keys are those sharing its prefix, so its parent extends it towards the
// neighbour sharing the longer prefix (never a tie: the keys are unique and sorted), and splits
// between the node and that neighbour.
struct RadixTreeParent {
  uint split;      // the parent's children cover [parent first, split] and [split + 1, parent last]
  bool left_side;  // the node is the parent's first child: it ends at the split
  int prefix;      // the parent's common prefix: sorted position k is in the parent iff
                   // radix_tree_delta(k, a position of the node) >= prefix
};

// The parent of the node covering [first, last], which is not the root.
SST_FUNC RadixTreeParent radix_tree_parent(RADIX_TREE_KEYS_PARAM int n, int first, int last) {
  int before = radix_tree_delta(RADIX_TREE_KEYS_ARG n, first, first - 1);
  int after = radix_tree_delta(RADIX_TREE_KEYS_ARG n, last, last + 1);
  RadixTreeParent p;
  p.left_side = after > before;
  p.split = uint(p.left_side ? last : first - 1);
  p.prefix = max(before, after);
  return p;
}

// The node index (Karras's layout above) of the node covering [first, last]: a second child is
// numbered by its first position, a first child by its last, the root 0, a leaf n - 1 + position.
SST_FUNC uint radix_tree_index(int n, int first, int last, bool left_side) {
  if (first == last) return uint(n - 1 + first);
  if (first == 0 && last == n - 1) return 0u;
  return uint(left_side ? last : first);
}

SST_END

#endif  // SST_CORE_LIGHTTREE_RADIX_TREE_NODE_H
