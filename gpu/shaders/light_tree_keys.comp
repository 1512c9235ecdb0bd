#version 450
#extension GL_GOOGLE_include_directive : require
// Sort keys of the GPU light-tree build (core/lighttree/sort_key.h), one invocation per VPL i:
// keys[i] = vpl_sort_key of VPL i, ids[i] = i.
//
// Bindings: 0 GpuVpl vpls[], 1 uvec2 keys[], 2 uint ids[]. Push: LightTreeBuildPush (count,
// grid_origin, grid_scale; the grid is MortonGrid::over(vpl bounds), computed on the host).
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"
#include "core/lighttree/sort_key.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = 1) writeonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = 2) writeonly buffer Ids { uint ids[]; };

void main() {
  uint i = ltb_index();
  if (i >= ltb.count) return;
  keys[i] = vpl_sort_key(vpls[i].position, vpls[i].normal, i, ltb.grid_origin, ltb.grid_scale);
  ids[i] = i;
}
