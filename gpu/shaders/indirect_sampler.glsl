// The indirect estimators (core/manylight/indirect_estimate.h) on the GPU: their hooks bound to
// the sampler's buffers and to the flat BVH's shadow rays.
//
// The includer declares, before including this file:
//   MANY_LIGHT_BUFFERS(first)     the sampler's inputs (core/manylight/many_light_layout.h)
//   the flat BVH traversal        core/accel/bvh_traverse.h with BVH_NODE / BVH_TRIANGLE
//   SCENE_RAY_EPSILON             EmbreeAccel's epsilon_ (core/accel/ray_offset.h)
#ifndef SST_GPU_SHADERS_INDIRECT_SAMPLER_GLSL
#define SST_GPU_SHADERS_INDIRECT_SAMPLER_GLSL
#include "core/vpl/vpl.h"
#include "core/accel/ray_offset.h"

Vpl ml_vpl(uint j) {
  GpuVpl g = ml_vpls[j];
  Vpl v;
  v.position = g.position;
  v.normal = g.normal;
  v.intensity = g.intensity;
  return v;
}

// An overflowing BVH stack (never, for a built tree) counts as occluded.
bool ml_occluded(vec3 x, vec3 ng, vec3 p, vec3 n) {
  vec3 origin, dir;
  float tmax;
  shadow_ray_segment(SCENE_RAY_EPSILON, x, ng, p, n, origin, dir, tmax);
  return bvh_occluded(origin, dir, 0.0, tmax) != BVH_VISIBLE;
}

#define ML_CTX_PARAM
#define ML_CTX
#define ML_PARAMS ml_params
#define ML_NODE(i) ml_nodes[i]
#define ML_VPL(j) ml_vpl(j)
#define ML_CUT_NODE(i) ml_cut_nodes[i]
#define ML_CUT_SIZE(b) ml_cut_sizes[b]
#define ML_CUT_GUIDE(b) ml_cut_guides[b]
#define ML_MOCK_CUT(j) ml_mock_cut[j]
#define ML_OCCLUDED(x, ng, p, n) ml_occluded(x, ng, p, n)
#define ML_COUNT_ITERATION() BVH_COUNT_ITERATION()
#include "core/manylight/indirect_estimate.h"

#endif
