// The ray-tracing BVH as it crosses the host/GPU boundary, defined once for C++ and
// GLSL. In C++ the structures live in namespace sst::glsl and are built from glm types, with
// static_asserts on size and offsets; in GLSL the same text declares plain structs for std430
// buffers (include with GL_GOOGLE_include_directive). Built by core/accel/flat_bvh.cpp, traversed
// by core/accel/bvh_traverse.h.
//
// Buffers (all std430, no vec3 arrays: every vec3 is followed by a 4-byte scalar, which std430
// packs into the vec3's 16-byte slot, exactly like the C++ layout):
//   BvhNode     nodes[]      32 bytes each, depth first: node 0 is the root, the left child of an
//                            inner node i is node i + 1, its right child is first_or_right.
//   BvhTriangle triangles[]  48 bytes each, in leaf order: a leaf owns the contiguous range
//                            [first_or_right, first_or_right + count). With spatial splits one
//                            scene triangle may be referenced by several leaves (copied).
// Triangles are stored as their three vertices, not as vertex + edges: the watertight test needs
// the exact vertex coordinates, so that two triangles sharing an edge compute that edge's
// function from bit-identical inputs.
#ifndef SST_CORE_ACCEL_BVH_LAYOUT_H
#define SST_CORE_ACCEL_BVH_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec2;
using glm::vec3;
#endif

// Entries of the traversal stack. The builder guarantees max leaf depth <= BVH_STACK_SIZE, which
// bounds the stack (one entry per inner node on the current path); the traversal still checks
// and reports BVH_STACK_OVERFLOW instead of dropping a subtree.
#define BVH_STACK_SIZE 32

// BvhNode.count_and_flags: leaf when BVH_LEAF_FLAG is set, with the triangle count in the low 31
// bits (a leaf of 0 triangles is the root of an empty scene). An inner node keeps the axis
// (0, 1, 2) along which its children are separated in the low 2 bits: traversal visits first
// the child on the side the ray comes from.
#define BVH_LEAF_FLAG 0x80000000u
#define BVH_COUNT_MASK 0x7FFFFFFFu
#define BVH_AXIS_MASK 3u

// BvhHit.triangle: no hit, and "the traversal stack overflowed" (cannot happen for a tree that
// build_flat_bvh returned; reported rather than silently missing geometry).
#define BVH_INVALID_TRIANGLE 0xFFFFFFFFu
#define BVH_STACK_OVERFLOW 0xFFFFFFFEu

struct BvhNode {
  vec3 bounds_min;
  uint first_or_right;   // leaf: first triangle in triangles[]; inner: index of the right child
  vec3 bounds_max;
  uint count_and_flags;  // see BVH_LEAF_FLAG
};

// BvhTriangle.flags: the triangle's material has an alpha test (SceneMaterial::alpha_cutoff > 0),
// which the traversal calls BVH_ALPHA_TEST for (bvh_traverse.h).
#define BVH_TRIANGLE_ALPHA_TESTED 1u

struct BvhTriangle {
  vec3 v0;
  uint triangle;  // index of the triangle in the scene (Scene::triangles)
  vec3 v1;
  uint flags;     // BVH_TRIANGLE_*
  vec3 v2;
  uint reserved;  // 0
};

// A ray as a shader reads it (e.g. gpu/shaders/bvh_trace_test.comp). t is in units of
// |direction|; hits are accepted for tmin <= t < tmax.
struct BvhRay {
  vec3 origin;
  float tmin;
  vec3 direction;
  float tmax;
};

// Result of a closest-hit query: on a miss triangle == BVH_INVALID_TRIANGLE and t == tmax.
// (u, v) are Embree's barycentrics: p = (1 - u - v) v0 + u v1 + v v2, with v0, v1, v2 in the
// vertex order of Scene::triangles[triangle].
struct BvhHit {
  float t;
  uint triangle;
  float u;
  float v;
};

// lavapipe ends all loops of a shader invocation after 65535 iterations (bvh_traverse.h). This
// is the loop iterations of one SIMD group (subgroup) past which that limit is near: a group's
// loops go on while any of its lanes is active, so the group iterates at most the sum of its
// lanes' counts; the margin below 65535 is for the shaders' other, short loops.
#define BVH_LAVAPIPE_LOOP_BUDGET 64000u

#ifdef __cplusplus
static_assert(sizeof(BvhNode) == 32);
static_assert(offsetof(BvhNode, bounds_min) == 0);
static_assert(offsetof(BvhNode, first_or_right) == 12);
static_assert(offsetof(BvhNode, bounds_max) == 16);
static_assert(offsetof(BvhNode, count_and_flags) == 28);
static_assert(sizeof(BvhTriangle) == 48);
static_assert(offsetof(BvhTriangle, v0) == 0);
static_assert(offsetof(BvhTriangle, triangle) == 12);
static_assert(offsetof(BvhTriangle, v1) == 16);
static_assert(offsetof(BvhTriangle, flags) == 28);
static_assert(offsetof(BvhTriangle, v2) == 32);
static_assert(offsetof(BvhTriangle, reserved) == 44);
static_assert(sizeof(BvhRay) == 32);
static_assert(offsetof(BvhRay, origin) == 0);
static_assert(offsetof(BvhRay, tmin) == 12);
static_assert(offsetof(BvhRay, direction) == 16);
static_assert(offsetof(BvhRay, tmax) == 28);
static_assert(sizeof(BvhHit) == 16);
static_assert(offsetof(BvhHit, t) == 0);
static_assert(offsetof(BvhHit, triangle) == 4);
static_assert(offsetof(BvhHit, u) == 8);
static_assert(offsetof(BvhHit, v) == 12);
}  // namespace sst::glsl

namespace sst {
using glsl::BvhHit;
}  // namespace sst
#endif

#endif  // SST_CORE_ACCEL_BVH_LAYOUT_H
