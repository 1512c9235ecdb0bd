// One node of a light tree (light_tree.h), leaf or internal, as both backends read it (shared
// C++/GLSL source): plain data in a flat array, uploaded to the GPU as is. Six 16-byte rows (a vec3
// and a 4-byte scalar each, which is also std430's layout of a vec3 followed by a scalar), 96
// bytes, the size the SST paper reports, and no padding bytes, so two trees compare with memcmp.
#ifndef SST_CORE_LIGHTTREE_LIGHT_NODE_H
#define SST_CORE_LIGHTTREE_LIGHT_NODE_H
#include "core/math/vector_math.h"

SST_BEGIN

// "No node" (an empty tree's root) and "no VPL" (a padding leaf's VPL index).
SST_CONSTANT uint kNoNode = 0xFFFFFFFFu;
// LightNode::flags.
SST_CONSTANT uint kLightNodeLeaf = 1u;      // no children; `left` is the VPL index
SST_CONSTANT uint kLightNodeSuitable = 2u;  // SST: v >= v_min and sigma_z <= sigma_max * D

struct LightNode {
  vec3 bounds_lo;  // AABB of the subtree's VPL positions; empty (lo = +inf, hi = -inf) for no VPLs
  uint left;       // internal: first child's node index; leaf: VPL index, kNoNode for padding
  vec3 bounds_hi;
  uint right;      // internal: second child's node index; leaf: kNoNode
  vec3 intensity;  // sum of the subtree's VPL intensities (RGB, fp32: fp16 overflows at 65504)
  uint vpl_count;
  vec3 mean;         // SST p: luminance-weighted mean position
  float similarity;  // SST v = v1 v2 max(n1.n2, 0); 1 at leaves
  vec3 normal;       // SST n: unit; defines the local basis basis_from_normal(normal)
  float sigma_z;     // SST sqrt(variance.z); 0 at leaves
  vec3 variance;     // SST s2 in the local basis (x, y on the tangent plane, z along normal)
  uint flags;        // kLightNode*
#ifdef __cplusplus
  static constexpr uint kLeaf = kLightNodeLeaf;
  static constexpr uint kSuitable = kLightNodeSuitable;
  bool is_leaf() const { return (flags & kLeaf) != 0; }
  bool suitable() const { return (flags & kSuitable) != 0; }
  bool empty() const { return vpl_count == 0; }
  Bounds3 bounds() const { return {bounds_lo, bounds_hi}; }
  uint vpl() const { return left; }  // leaves only
#endif
};

SST_FUNC bool light_node_is_leaf(SST_IN(LightNode) node) { return (node.flags & kLightNodeLeaf) != 0u; }
SST_FUNC bool light_node_suitable(SST_IN(LightNode) node) { return (node.flags & kLightNodeSuitable) != 0u; }
SST_FUNC bool light_node_empty(SST_IN(LightNode) node) { return node.vpl_count == 0u; }

SST_END

#ifdef __cplusplus
#include <cstddef>
#include <type_traits>
namespace sst {
static_assert(sizeof(LightNode) == 96 && alignof(LightNode) == 4);
static_assert(offsetof(LightNode, left) == 12 && offsetof(LightNode, bounds_hi) == 16 &&
              offsetof(LightNode, right) == 28 && offsetof(LightNode, intensity) == 32 &&
              offsetof(LightNode, vpl_count) == 44 && offsetof(LightNode, mean) == 48 &&
              offsetof(LightNode, similarity) == 60 && offsetof(LightNode, normal) == 64 &&
              offsetof(LightNode, sigma_z) == 76 && offsetof(LightNode, variance) == 80 &&
              offsetof(LightNode, flags) == 92);
static_assert(std::is_trivially_copyable_v<LightNode> && std::is_standard_layout_v<LightNode>);
}  // namespace sst
#endif

#endif  // SST_CORE_LIGHTTREE_LIGHT_NODE_H
