#version 450
#extension GL_GOOGLE_include_directive : require
// The leaves of the GPU perfect (heap) light tree, laid out as build_perfect_tree
// (core/lighttree/perfect_tree_builder.cpp) lays them out, made by core/lighttree/substitute.h.
// Invocation i < count writes leaf first_leaf + i = make_leaf of VPL ids[i] (ids sorted by key);
// count <= i < first_leaf writes a padding leaf there; invocation 0 also writes node 0, the
// unused padding leaf that keeps the heap's indices 1-based.
//
// Dispatch: first_leaf (L, the power of two >= count) invocations, ltb_index().
// Bindings: 0 GpuVpl vpls[], 1 uint ids[] (sorted), 2 LightNode nodes[] (2L). Push: count (VPLs),
// first_leaf (L), v_min, sigma_max_abs.
#include "core/manylight/many_light_layout.h"
#include "core/lighttree/light_tree_build_layout.h"
#include "core/lighttree/substitute.h"

layout(local_size_x = LTB_GROUP_SIZE) in;
layout(std430, binding = 0) readonly buffer Vpls { GpuVpl vpls[]; };
layout(std430, binding = 1) readonly buffer Ids { uint ids[]; };
layout(std430, binding = 2) writeonly buffer Nodes { LightNode nodes[]; };

void main() {
  uint i = ltb_index();
  if (i >= ltb.first_leaf) return;
  SubstituteThresholds thresholds = SubstituteThresholds(ltb.v_min, ltb.sigma_max_abs);
  if (i == 0u) nodes[0] = make_padding_leaf(thresholds);
  if (i < ltb.count) {
    uint vpl = ids[i];
    nodes[ltb.first_leaf + i] = make_leaf(vpls[vpl].position, vpls[vpl].normal, vpls[vpl].intensity, vpl, thresholds);
  } else {
    nodes[ltb.first_leaf + i] = make_padding_leaf(thresholds);
  }
}
