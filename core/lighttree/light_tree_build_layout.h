// The GPU light-tree build's push constants (gpu/light_tree_build_pass.h), defined once for C++ and
// GLSL: the parameters LightTreeBuilder::build passes between its stages
// (core/lighttree/light_tree.cpp): the Morton grid of sort_key.h, the radix sort's digit, the
// node layout of a radix or perfect (heap) tree and the SST thresholds of substitute.h.
//
// Sort keys cross the boundary as uvec2 (x = bits 0..31, y = bits 32..63: a uint64_t's bytes on
// a little-endian host), so that no shader needs the shaderInt64 feature.
#ifndef SST_CORE_LIGHTTREE_LIGHT_TREE_BUILD_LAYOUT_H
#define SST_CORE_LIGHTTREE_LIGHT_TREE_BUILD_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
#endif

// local_size_x of every light_tree_*.comp shader; also the radix sort's tile (elements per
// workgroup) and its digit count (8-bit digits).
#define LTB_GROUP_SIZE 256u
#define LTB_RADIX 256u

struct LightTreeBuildPush {
  uint count;          // elements: VPLs (keys, sort, merge, perfect leaves), internal nodes
                       // (hierarchy) or the nodes of one level (perfect merge)
  uint shift;          // sort: the digit's lowest key bit
  uint tile_count;     // sort: tiles of LTB_GROUP_SIZE keys, ceil(VPLs / LTB_GROUP_SIZE)
  uint first_leaf;     // hierarchy, merge: node index of the first leaf (VPLs - 1); perfect
                       // leaves: L (leaves, a power of two); perfect merge: the level's first node
  vec3 grid_origin;    // keys: MortonGrid::origin
  float v_min;         // merge, perfect: SubstituteThresholds::v_min
  vec3 grid_scale;     // keys: MortonGrid::scale
  float sigma_max_abs; // merge, perfect: SubstituteThresholds::sigma_max_abs
};

#ifdef __cplusplus
static_assert(sizeof(LightTreeBuildPush) == 48);
static_assert(offsetof(LightTreeBuildPush, grid_origin) == 16 && offsetof(LightTreeBuildPush, v_min) == 28 &&
              offsetof(LightTreeBuildPush, grid_scale) == 32 && offsetof(LightTreeBuildPush, sigma_max_abs) == 44);
}  // namespace sst::glsl
#else
layout(push_constant) uniform LightTreeBuildPushBlock { LightTreeBuildPush ltb; };

// The flat index of this invocation in a dispatch of (x, y) workgroups (y > 1 past 65535 groups).
uint ltb_index() {
  uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  return group * LTB_GROUP_SIZE + gl_LocalInvocationID.x;
}
uint ltb_group() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }
#endif

#endif  // SST_CORE_LIGHTTREE_LIGHT_TREE_BUILD_LAYOUT_H
