// The indirect estimators on the GPU: their hooks (core/manylight/estimator.h) bound to the
// sampler's buffers and to the flat BVH's shadow rays, each method's estimate
// (core/manylight/<name>/<name>_estimate.h), and estimate_indirect, the switch over the list of
// methods (core/manylight/many_light_methods.h) that runs the one SamplerParams.method names (the
// pipeline's kSpecManyLightMethod where it fixes one, gpu/shaders/specialization.glsl).
//
// The includer declares, before including this file:
//   MANY_LIGHT_BUFFERS(first)     the sampler's inputs (core/manylight/many_light_layout.h)
//   the flat BVH traversal        core/accel/bvh_traverse.h with BVH_NODE / BVH_TRIANGLE
//   SCENE_RAY_EPSILON             EmbreeAccel's epsilon_ (core/accel/ray_offset.h)
#ifndef SST_GPU_SHADERS_INDIRECT_SAMPLER_GLSL
#define SST_GPU_SHADERS_INDIRECT_SAMPLER_GLSL
#include "core/vpl/vpl.h"
#include "gpu/shaders/specialization.glsl"
#include "core/accel/ray_offset.h"
#include "gpu/shaders/ray_queries.glsl"

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
  shadow_ray_segment(SCENE_RAY_EPSILON, x, ng, SCENE_RAY_EPSILON, p, n, origin, dir, tmax);
  return ray_occluded(origin, dir, tmax);
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
// One line per method of the list.
#include "core/manylight/exhaustive/exhaustive_estimate.h"
#include "core/manylight/uniform/uniform_estimate.h"
#include "core/manylight/slc/slc_estimate.h"
#include "core/manylight/sst/sst_estimate.h"
#include "core/manylight/rtslc/rtslc_estimate.h"
#include "core/manylight/hybrid/hybrid_estimate.h"

// One indirect estimate at a shading point by the method ml_params.method names: the per-pixel
// work of every VPL method. The pixel sampler continues the pixel sample's stream where the camera
// ray and the direct light left it. On the CPU, IndirectSampler::estimate calls the same
// estimate_<name>.
IndirectEstimate estimate_indirect(ShadingPoint sp, inout PixelSampler ps) {
  switch (kSpecManyLightMethod != kSpecUnset ? kSpecManyLightMethod : ml_params.method) {
#define ML_ESTIMATE_CASE(name, id) \
  case id:                         \
    return estimate_##name(sp, ps);
    SST_MANY_LIGHT_METHODS(ML_ESTIMATE_CASE)
#undef ML_ESTIMATE_CASE
  }
  return indirect_estimate_zero();
}

#endif
