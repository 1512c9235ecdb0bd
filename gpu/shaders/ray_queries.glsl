// The RAY_* hooks of the shared path kernels (core/pt/trace_path.h lists them) bound to the flat
// BVH: a closest-hit query over [0, inf) and a shadow query over [0, tmax).
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
// The traversals are called through an out parameter and a function of their own: used directly in
// the path's expressions, glslang's `precise` propagation follows them into the traversal loops
// and takes all memory.
void ray_closest_hit_into(vec3 origin, vec3 dir, out BvhHit hit) { hit = bvh_intersect(origin, dir, 0.0, kInf); }
BvhHit ray_closest_hit(vec3 origin, vec3 dir) {
  BvhHit hit;
  ray_closest_hit_into(origin, dir, hit);
  return hit;
}
bool ray_occluded(vec3 origin, vec3 dir, float tmax) { return bvh_occluded(origin, dir, 0.0, tmax) != BVH_VISIBLE; }
#define RAY_INTERSECT(origin, dir) ray_closest_hit(origin, dir)
#define RAY_OCCLUDED(origin, dir, tmax) ray_occluded(origin, dir, tmax)
#define RAY_EPSILON SCENE_RAY_EPSILON

#endif  // SST_GPU_SHADERS_RAY_QUERIES_GLSL
