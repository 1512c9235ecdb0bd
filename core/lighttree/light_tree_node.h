// Node i of a light tree (core/lighttree/light_tree.h), in shared C++/GLSL source
// (core/math/cpu_gpu.h): a node below `stored` is read from the node array; any other is a leaf,
// made from its VPL (make_leaf), or a perfect tree's padding leaf past the VPLs. LightTree::node
// and the GPU build's shaders read their trees' nodes through these functions.
//
// Convention for the including file, C++ or GLSL, before the #include (as radix_tree_node.h):
//   LIGHT_TREE_STORED(i)      stored node i (a LightNode)
//   LIGHT_TREE_LEAF_VPL(j)    the VPL index of leaf position j < vpl_count (a uint)
//   LIGHT_TREE_VPL(v)         VPL v: an expression with fields position, normal and intensity
//   LIGHT_TREE_PARAM          optional: a leading parameter of the functions below, with its
//                             trailing comma, through which the hooks reach the tree (C++:
//                             `const LightTree& tree,`); empty by default (GLSL buffers are globals)
//   LIGHT_TREE_ARG            with LIGHT_TREE_PARAM: the same parameter as an argument
#ifndef SST_CORE_LIGHTTREE_LIGHT_TREE_NODE_H
#define SST_CORE_LIGHTTREE_LIGHT_TREE_NODE_H
#include "core/lighttree/substitute.h"

#if !defined(LIGHT_TREE_STORED) || !defined(LIGHT_TREE_LEAF_VPL) || !defined(LIGHT_TREE_VPL)
#error "define LIGHT_TREE_STORED, LIGHT_TREE_LEAF_VPL and LIGHT_TREE_VPL before including light_tree_node.h"
#endif
#ifndef LIGHT_TREE_PARAM
#define LIGHT_TREE_PARAM
#endif
#ifndef LIGHT_TREE_ARG
#define LIGHT_TREE_ARG
#endif

SST_BEGIN

// Leaf position j (node first_leaf + j) of a tree over vpl_count VPLs.
SST_FUNC LightNode light_tree_leaf(LIGHT_TREE_PARAM uint j, uint vpl_count, SST_IN(SubstituteThresholds) t) {
  if (j >= vpl_count) return make_padding_leaf(t);
  uint vpl = LIGHT_TREE_LEAF_VPL(j);
  return make_leaf(LIGHT_TREE_VPL(vpl).position, LIGHT_TREE_VPL(vpl).normal, LIGHT_TREE_VPL(vpl).intensity, vpl, t);
}

// Node i of a tree whose nodes [0, stored) are in its array.
SST_FUNC LightNode light_tree_node(LIGHT_TREE_PARAM uint i, uint stored, uint first_leaf, uint vpl_count,
                                   SST_IN(SubstituteThresholds) t) {
  if (i < stored) return LIGHT_TREE_STORED(i);
  return light_tree_leaf(LIGHT_TREE_ARG i - first_leaf, vpl_count, t);
}

SST_END

#endif  // SST_CORE_LIGHTTREE_LIGHT_TREE_NODE_H
