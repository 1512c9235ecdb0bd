// Traces a batch of rays through the flat BVH (core/accel/bvh_traverse.h, the same code the CPU
// runs in core/accel/flat_bvh.cpp): the cross-backend test of the traversal. One invocation per
// ray; closest hit to hits[], occlusion over the same [tmin, tmax) to occluded[]
// (BVH_VISIBLE, BVH_OCCLUDED or BVH_STACK_OVERFLOW).
// Compile: glslc gpu/shaders/bvh_trace_test.comp -o bvh_trace_test.spv (includes are relative).
#version 450
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "core/accel/bvh_layout.h"

layout(std430, set = 0, binding = 0) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, set = 0, binding = 1) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };
layout(std430, set = 0, binding = 2) readonly buffer Rays { BvhRay rays[]; };
layout(std430, set = 0, binding = 3) writeonly buffer Hits { BvhHit hits[]; };
layout(std430, set = 0, binding = 4) writeonly buffer Occluded { uint occluded[]; };

layout(push_constant) uniform Params { uint ray_count; } params;

#define BVH_NODE(i) bvh_nodes[i]
#define BVH_TRIANGLE(i) bvh_triangles[i]
#include "core/accel/bvh_traverse.h"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.ray_count) return;
  BvhRay ray = rays[i];
  hits[i] = bvh_intersect(ray.origin, ray.direction, ray.tmin, ray.tmax);
  occluded[i] = bvh_occluded(ray.origin, ray.direction, ray.tmin, ray.tmax);
}
