// The RAY_* hooks of the shared path kernels (core/pt/trace_path.h lists them) bound to the flat
// BVH, or in the ray-query builds (SST_RAY_QUERY) to the scene's acceleration structure: a
// closest-hit query over [0, inf) and a shadow query over [0, tmax).
//
// The including shader declares, before including this file: BVH_NODE / BVH_TRIANGLE and
// includes core/accel/bvh_traverse.h, and SCENE_RAY_EPSILON (EmbreeAccel's scene_ray_epsilon, for
// core/accel/ray_offset.h). Where the CPU uses Embree, a ray that grazes an edge may hit on one
// backend and miss on the other (rare; see tests/gpu/path_trace_pass_test.cpp); with --accel flat
// the CPU traverses this BVH too. A BVH stack overflow (never seen: the builder bounds the depth)
// is reported to the kernels (BVH_STACK_OVERFLOW) and counts as occluded for a shadow ray.
#ifndef SST_GPU_SHADERS_RAY_QUERIES_GLSL
#define SST_GPU_SHADERS_RAY_QUERIES_GLSL

#define RAY_CTX_PARAM
#define RAY_CTX
#if SST_RAY_QUERY
// The ray-query builds trace the scene's acceleration structure (gpu/shaders/scene_accel.glsl):
// a candidate hit on the non-opaque geometry (alpha-tested materials) counts where the flat
// BVH's alpha test passes, so both structures see the same surfaces; only which of two hits on a
// shared edge or a coplanar overlap counts may differ.
// A ray query's origin and direction must be finite and the direction non-zero (the flat BVH
// misses such rays; a driver may do anything with them).
bool ray_query_valid(vec3 origin, vec3 dir, float tmax) {
  return is_finite3(origin) && is_finite3(dir) && dot(dir, dir) > 0.0 && tmax > 0.0;
}
// Runs query q to its end, keeping the candidate hits (non-opaque geometry) that pass the alpha test.
void ray_query_traverse(rayQueryEXT q) {
  while (rayQueryProceedEXT(q)) {
    if (rayQueryGetIntersectionTypeEXT(q, false) == gl_RayQueryCandidateIntersectionTriangleEXT &&
        BVH_ALPHA_TEST(uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, false)), rayQueryGetIntersectionBarycentricsEXT(q, false)))
      rayQueryConfirmIntersectionEXT(q);
  }
}
void ray_closest_hit_into(vec3 origin, vec3 dir, out BvhHit hit) {
  hit.t = kInf;
  hit.triangle = BVH_INVALID_TRIANGLE;
  hit.u = 0.0;
  hit.v = 0.0;
  if (!ray_query_valid(origin, dir, kInf)) return;
  rayQueryEXT q;
  rayQueryInitializeEXT(q, scene_top_level, gl_RayFlagsNoneEXT, 0xFFu, origin, 0.0, dir, kInf);
  ray_query_traverse(q);
  if (rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionTriangleEXT) {
    vec2 b = rayQueryGetIntersectionBarycentricsEXT(q, true);
    hit.t = rayQueryGetIntersectionTEXT(q, true);
    hit.triangle = uint(rayQueryGetIntersectionPrimitiveIndexEXT(q, true));
    hit.u = b.x;
    hit.v = b.y;
  }
}
bool ray_occluded(vec3 origin, vec3 dir, float tmax) {
  if (!ray_query_valid(origin, dir, tmax)) return false;
  rayQueryEXT q;
  rayQueryInitializeEXT(q, scene_top_level, gl_RayFlagsTerminateOnFirstHitEXT, 0xFFu, origin, 0.0, dir, tmax);
  ray_query_traverse(q);
  return rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionTriangleEXT;
}
#else
// The traversals are called through an out parameter and a function of their own: used directly in
// the path's expressions, glslang's `precise` propagation follows them into the traversal loops
// and takes all memory.
void ray_closest_hit_into(vec3 origin, vec3 dir, out BvhHit hit) { hit = bvh_intersect(origin, dir, 0.0, kInf); }
bool ray_occluded(vec3 origin, vec3 dir, float tmax) { return bvh_occluded(origin, dir, 0.0, tmax) != BVH_VISIBLE; }
#endif
BvhHit ray_closest_hit(vec3 origin, vec3 dir) {
  BvhHit hit;
  ray_closest_hit_into(origin, dir, hit);
  return hit;
}
#define RAY_INTERSECT(origin, dir) ray_closest_hit(origin, dir)
#define RAY_OCCLUDED(origin, dir, tmax) ray_occluded(origin, dir, tmax)
#define RAY_EPSILON SCENE_RAY_EPSILON

#endif  // SST_GPU_SHADERS_RAY_QUERIES_GLSL
