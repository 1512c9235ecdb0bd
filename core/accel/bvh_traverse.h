// Ray traversal of the flat BVH (core/accel/bvh_layout.h), written once in the common subset of
// C++ (glm) and GLSL 4.50, so that the CPU tests (core/accel/flat_bvh.cpp) and the Vulkan
// shaders run literally the same code.
//
// Convention for the including file, C++ or GLSL, before the #include:
//   BVH_NODE(i)        an expression of type BvhNode: node i (GLSL: `nodes[i]` of an SSBO)
//   BVH_TRIANGLE(i)    an expression of type BvhTriangle: triangle reference i
//   BVH_CONTEXT_PARAM  optional: an extra leading parameter of bvh_intersect / bvh_occluded,
//                      with its trailing comma, through which BVH_NODE/BVH_TRIANGLE reach the
//                      buffers (C++: `const sst::FlatBvh& bvh,`); empty by default (GLSL
//                      buffers are globals).
//   BVH_CONTEXT_ARG    with BVH_CONTEXT_PARAM: the same parameter as an argument (`bvh,`).
//   BVH_ALPHA_TEST(triangle, b)  optional: whether a hit on scene triangle `triangle` at
//                      barycentrics b (vec2) counts (core/shading/surface_eval.h's
//                      triangle_alpha_passes); asked only for triangles flagged
//                      BVH_TRIANGLE_ALPHA_TESTED. Without it every hit counts.
// The common subset used here: structs built member by member (no constructors, no aggregate
// initialisation), functions returning structs, BVH_IN/BVH_INOUT for parameter qualifiers
// (C++ const& / &, GLSL in / inout), BVH_FUNC before every function (C++ inline), vecN
// operators and min/max/abs from glm in C++, no swizzles (sst builds with GLM_FORCE_XYZW_ONLY),
// float literals with an f suffix, uint literals with u, include guards not #pragma once.
//
// Queries (tmin <= t < tmax, t in units of |direction|, direction need not be unit length):
//   BvhHit bvh_intersect(origin, direction, tmin, tmax)   closest hit, see BvhHit
//   uint   bvh_occluded(origin, direction, tmin, tmax)    BVH_VISIBLE, BVH_OCCLUDED or
//                                                        BVH_STACK_OVERFLOW
//
// Robustness:
// - Ray-triangle: the watertight test of Woop, Benthin & Wald, "Watertight Ray/Triangle
//   Intersection" (JCGT 2013): vertices are translated to the ray origin and sheared so that the
//   ray is the +z axis; the 2D edge functions of two triangles sharing an edge are then exact
//   negations of each other, so a ray through a shared edge or vertex hits at least one of them.
//   t, u and v of an accepted hit are then recomputed from the triangle's own edges (plane
//   distance and Moeller-Trumbore; accurate for slivers, where the sheared edge functions cancel). Edge functions of exactly 0
//   count as inside on both sides (the paper's double-precision
//   recomputation of 0 is not done: it would need shaderFloat64). Double-sided (no culling).
//   For the edge functions to be exact negations no multiply-add may be fused: GLSL marks them
//   `precise`; C++ must compile this with FP contraction off (core/accel/flat_bvh.cpp sets it).
// - Ray-box: slab test with the far distance scaled by 1 + 2 gamma(3) (Ize, "Robust BVH Ray
//   Traversal", JCGT 2013), so that rounding cannot cull a box the ray touches; a zero direction
//   component is replaced by +-1e-30 so that no 0 * inf = NaN arises.
// - Stack: BVH_STACK_SIZE entries; the builder bounds the tree depth by it. An overflow ends the
//   query with BVH_STACK_OVERFLOW (hit.triangle or the occlusion result), never a silent miss.
#ifndef SST_CORE_ACCEL_BVH_TRAVERSE_H
#define SST_CORE_ACCEL_BVH_TRAVERSE_H

#include "bvh_layout.h"

#ifndef BVH_NODE
#error "define BVH_NODE(i) before including bvh_traverse.h"
#endif
#ifndef BVH_TRIANGLE
#error "define BVH_TRIANGLE(i) before including bvh_traverse.h"
#endif
#ifndef BVH_CONTEXT_PARAM
#define BVH_CONTEXT_PARAM
#endif
#ifndef BVH_CONTEXT_ARG
#define BVH_CONTEXT_ARG
#endif
#ifndef BVH_ALPHA_TEST
#define BVH_ALPHA_TEST(triangle, b) true
#endif

#ifdef __cplusplus
namespace sst::glsl {
using glm::abs;
using glm::cross;
using glm::dot;
using glm::max;
using glm::min;
#define BVH_FUNC inline
#define BVH_IN(T) const T&
#define BVH_INOUT(T) T&
#define BVH_PRECISE
#else
#define BVH_FUNC
#define BVH_IN(T) in T
#define BVH_INOUT(T) inout T
#define BVH_PRECISE precise
#endif

#define BVH_VISIBLE 0u
#define BVH_OCCLUDED 1u
// 1 + 2 gamma(3), gamma(n) = n eps / (1 - n eps), eps = 2^-24, rounded up (4 ulps above 1).
#define BVH_BOX_GROW 1.0000005f

// Per-ray constants of the box and triangle tests.
struct BvhRayPre {
  vec3 origin;
  vec3 direction;
  vec3 inv_dir;    // 1 / direction, zero components replaced by +-1e-30
  float tmin;
  int kx;          // shear permutation: kz = dominant axis of the direction
  int ky;
  int kz;
  float sx;        // shear constants
  float sy;
  float sz;
  uint neg_mask;   // bit a set when direction[a] < 0
};

BVH_FUNC float bvh_safe_rcp(float x) {
  return 1.0f / (abs(x) > 1e-30f ? x : (x >= 0.0f ? 1e-30f : -1e-30f));
}

BVH_FUNC BvhRayPre bvh_prepare_ray(vec3 origin, vec3 direction, float tmin) {
  BvhRayPre ray;
  ray.origin = origin;
  ray.direction = direction;
  ray.tmin = tmin;
  ray.inv_dir = vec3(bvh_safe_rcp(direction.x), bvh_safe_rcp(direction.y), bvh_safe_rcp(direction.z));
  ray.neg_mask = (direction.x < 0.0f ? 1u : 0u) | (direction.y < 0.0f ? 2u : 0u) | (direction.z < 0.0f ? 4u : 0u);
  vec3 ad = abs(direction);
  int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  int kx = kz + 1;
  if (kx == 3) kx = 0;
  int ky = kx + 1;
  if (ky == 3) ky = 0;
  // Swapping x and y when the ray points down its z keeps the triangles' winding.
  if (direction[kz] < 0.0f) {
    int swap_tmp = kx;
    kx = ky;
    ky = swap_tmp;
  }
  ray.kx = kx;
  ray.ky = ky;
  ray.kz = kz;
  ray.sx = direction[kx] / direction[kz];
  ray.sy = direction[ky] / direction[kz];
  ray.sz = 1.0f / direction[kz];
  return ray;
}

// Whether the ray meets the box [lo, hi] at a distance in [tmin, tmax] (conservatively).
BVH_FUNC bool bvh_hit_box(BVH_IN(BvhRayPre) ray, vec3 lo, vec3 hi, float tmax) {
  vec3 t0 = (lo - ray.origin) * ray.inv_dir;
  vec3 t1 = (hi - ray.origin) * ray.inv_dir;
  vec3 tn = min(t0, t1);
  vec3 tf = max(t0, t1);
  float tnear = max(max(tn.x, tn.y), max(tn.z, ray.tmin));
  float tfar = min(min(tf.x, tf.y), tf.z) * BVH_BOX_GROW;
  return tnear <= min(tfar, tmax);
}

// Watertight ray-triangle test; on a hit with tmin <= t < hit.t that passes the alpha test
// updates hit and returns true.
BVH_FUNC bool bvh_intersect_triangle(BVH_CONTEXT_PARAM BVH_IN(BvhRayPre) ray, BVH_IN(BvhTriangle) tri,
                                     BVH_INOUT(BvhHit) hit) {
  BVH_PRECISE vec3 a = tri.v0 - ray.origin;
  BVH_PRECISE vec3 b = tri.v1 - ray.origin;
  BVH_PRECISE vec3 c = tri.v2 - ray.origin;
  BVH_PRECISE float ax = a[ray.kx] - ray.sx * a[ray.kz];
  BVH_PRECISE float ay = a[ray.ky] - ray.sy * a[ray.kz];
  BVH_PRECISE float bx = b[ray.kx] - ray.sx * b[ray.kz];
  BVH_PRECISE float by = b[ray.ky] - ray.sy * b[ray.kz];
  BVH_PRECISE float cx = c[ray.kx] - ray.sx * c[ray.kz];
  BVH_PRECISE float cy = c[ray.ky] - ray.sy * c[ray.kz];
  // Scaled barycentrics: e0 weighs v0, e1 weighs v1, e2 weighs v2.
  BVH_PRECISE float e0 = cx * by - cy * bx;
  BVH_PRECISE float e1 = ax * cy - ay * cx;
  BVH_PRECISE float e2 = bx * ay - by * ax;
  if ((e0 < 0.0f || e1 < 0.0f || e2 < 0.0f) && (e0 > 0.0f || e1 > 0.0f || e2 > 0.0f)) return false;
  BVH_PRECISE float det = e0 + e1 + e2;
  if (det == 0.0f) return false;  // the ray lies in the triangle's plane
  BVH_PRECISE float az = ray.sz * a[ray.kz];
  BVH_PRECISE float bz = ray.sz * b[ray.kz];
  BVH_PRECISE float cz = ray.sz * c[ray.kz];
  BVH_PRECISE float t_scaled = e0 * az + e1 * bz + e2 * cz;
  float rcp_det = 1.0f / det;
  float t = t_scaled * rcp_det;
  float u = e1 * rcp_det;
  float v = e2 * rcp_det;
  // The test above decides hit or miss (watertight). Its t and barycentrics, though, come from
  // edge functions of origin-relative coordinates, which cancel for slivers seen from afar (t off
  // by 1e-4 relative on the staircase's 6 m x 2 mm triangles). Recompute them from the
  // triangle's own edges, as accurate as Embree's, where that is defined.
  vec3 edge1 = tri.v1 - tri.v0;
  vec3 edge2 = tri.v2 - tri.v0;
  vec3 pvec = cross(ray.direction, edge2);
  float mt_det = dot(edge1, pvec);
  if (mt_det != 0.0f) {
    float mt_rcp = 1.0f / mt_det;
    vec3 tvec = ray.origin - tri.v0;
    vec3 qvec = cross(tvec, edge1);
    u = min(max(dot(tvec, pvec) * mt_rcp, 0.0f), 1.0f);
    v = min(max(dot(ray.direction, qvec) * mt_rcp, 0.0f), 1.0f - u);
  }
  // t from the plane, with the normal from the two edges at the vertex opposite the longest edge
  // (the least parallel pair: no cancellation in the cross product for slivers).
  vec3 e12 = tri.v2 - tri.v1;
  vec3 e20 = tri.v0 - tri.v2;
  float l01 = dot(edge1, edge1);
  float l12 = dot(e12, e12);
  float l20 = dot(e20, e20);
  vec3 normal = cross(edge1, e12);
  vec3 base = tri.v1;
  if (l01 >= l12 && l01 >= l20) {
    normal = cross(e12, e20);
    base = tri.v2;
  } else if (l12 >= l20) {
    normal = cross(e20, edge1);
    base = tri.v0;
  }
  float plane_t = dot(base - ray.origin, normal) / dot(ray.direction, normal);
  if (abs(plane_t) <= 3.0e38f) t = plane_t;  // finite: not parallel to the plane
  if (!(t >= ray.tmin && t < hit.t)) return false;  // also rejects NaN (zero direction)
  if ((tri.flags & BVH_TRIANGLE_ALPHA_TESTED) != 0u && !(BVH_ALPHA_TEST(tri.triangle, vec2(u, v)))) return false;
  hit.t = t;
  hit.triangle = tri.triangle;
  hit.u = u;
  hit.v = v;
  return true;
}

// lavapipe (llvmpipe) ends every loop of a shader invocation once all its loops together have run
// 65535 iterations (LP_MAX_TGSI_LOOP_ITERATIONS), silently: the rest of the invocation then
// computes garbage. The traversal loops are where the iterations go, so the GLSL counts them in
// bvh_loop_iterations (per invocation), and the passes report samples that came near the limit
// instead of returning a wrong image.
#ifdef __cplusplus
#define BVH_COUNT_ITERATION()
#else
uint bvh_loop_iterations = 0u;
#define BVH_COUNT_ITERATION() ++bvh_loop_iterations
#endif

// The one traversal behind both queries: the closest hit with tmin <= t < tmax, or, when
// `any_hit`, the first hit found (its t need not be the closest). A stack overflow is reported as
// triangle == BVH_STACK_OVERFLOW.
BVH_FUNC BvhHit bvh_traverse(BVH_CONTEXT_PARAM vec3 origin, vec3 direction, float tmin, float tmax, bool any_hit) {
  BvhRayPre ray = bvh_prepare_ray(origin, direction, tmin);
  BvhHit hit;
  hit.t = tmax;
  hit.triangle = BVH_INVALID_TRIANGLE;
  hit.u = 0.0f;
  hit.v = 0.0f;
  uint stack[BVH_STACK_SIZE];
  int sp = 0;
  uint index = 0u;
  while (true) {
    BVH_COUNT_ITERATION();
    BvhNode node = BVH_NODE(index);
    if (bvh_hit_box(ray, node.bounds_min, node.bounds_max, hit.t)) {
      if ((node.count_and_flags & BVH_LEAF_FLAG) != 0u) {
        uint end = node.first_or_right + (node.count_and_flags & BVH_COUNT_MASK);
        for (uint i = node.first_or_right; i < end; ++i) {
          BVH_COUNT_ITERATION();
          if (bvh_intersect_triangle(BVH_CONTEXT_ARG ray, BVH_TRIANGLE(i), hit) && any_hit) return hit;
        }
      } else {
        if (sp == BVH_STACK_SIZE) {
          hit.triangle = BVH_STACK_OVERFLOW;
          return hit;
        }
        // Near child first: the left child is on the low side of the split axis.
        bool flip = ((ray.neg_mask >> (node.count_and_flags & BVH_AXIS_MASK)) & 1u) != 0u;
        stack[sp] = flip ? index + 1u : node.first_or_right;
        sp++;
        index = flip ? node.first_or_right : index + 1u;
        continue;
      }
    }
    if (sp == 0) break;
    sp--;
    index = stack[sp];
  }
  return hit;
}

// Closest hit with tmin <= t < tmax.
BVH_FUNC BvhHit bvh_intersect(BVH_CONTEXT_PARAM vec3 origin, vec3 direction, float tmin, float tmax) {
  return bvh_traverse(BVH_CONTEXT_ARG origin, direction, tmin, tmax, false);
}

// Any hit with tmin <= t < tmax: BVH_OCCLUDED, BVH_VISIBLE or BVH_STACK_OVERFLOW.
BVH_FUNC uint bvh_occluded(BVH_CONTEXT_PARAM vec3 origin, vec3 direction, float tmin, float tmax) {
  BvhHit hit = bvh_traverse(BVH_CONTEXT_ARG origin, direction, tmin, tmax, true);
  if (hit.triangle == BVH_STACK_OVERFLOW) return BVH_STACK_OVERFLOW;
  return hit.triangle == BVH_INVALID_TRIANGLE ? BVH_VISIBLE : BVH_OCCLUDED;
}

#ifdef __cplusplus
}  // namespace sst::glsl
#endif

#endif  // SST_CORE_ACCEL_BVH_TRAVERSE_H
