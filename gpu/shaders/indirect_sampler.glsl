// The GLSL twin of core/manylight/indirect_sampler.h and its six samplers (exhaustive, uniform,
// slc, sst, rtslc, hybrid; gpu/shaders/indirect/*.glsl): one indirect estimate at a shading point,
// from the state the CPU's IndirectSampler::prepare built and gpu_inputs handed over
// (core/manylight/many_light_layout.h): the same method, the same random numbers drawn in the same
// order from the pixel's PixelSampler, the same nodes visited and shadow rays traced, values equal
// to float rounding (see each method's file for where the CPU computes in double).
//
// The includer declares, before including this file:
//   MANY_LIGHT_BUFFERS(first)     the sampler's inputs (core/manylight/many_light_layout.h)
//   the flat BVH traversal        core/accel/bvh_traverse.h with BVH_NODE / BVH_TRIANGLE
//   SCENE_RAY_EPSILON             EmbreeAccel's epsilon_ (gpu/shaders/ray_offset.glsl)
// e.g.
//   #include "core/manylight/many_light_layout.h"
//   MANY_LIGHT_BUFFERS(0)
//   ... BVH buffers, #define BVH_NODE / BVH_TRIANGLE, #include "core/accel/bvh_traverse.h"
//   #define SCENE_RAY_EPSILON push.ray_epsilon
//   #include "gpu/shaders/indirect_sampler.glsl"
#ifndef SST_GPU_SHADERS_INDIRECT_SAMPLER_GLSL
#define SST_GPU_SHADERS_INDIRECT_SAMPLER_GLSL
#include "core/material/brdf.h"
#include "core/math/vector_math.h"
#include "core/rng/sobol_sampler.h"
#include "gpu/shaders/vpl_shading.glsl"

// A camera ray's first hit, ready to shade (sst::ShadingPoint).
struct ShadingPoint {
  vec3 p;
  vec3 ng;      // geometric normal on the viewer's side
  Basis basis;  // shading basis (basis.n = shading normal)
  vec3 wo;      // toward the viewer, in the shading frame
  Brdf brdf;
  int x;  // pixel
  int y;
};

struct IndirectEstimate {
  vec3 value;          // an estimate of sum_j contribution_j * visibility_j
  uint nodes_visited;  // tree nodes visited to draw the sample(s)
  uint shadow_rays;
};

IndirectEstimate indirect_estimate_zero() { return IndirectEstimate(vec3(0.0), 0u, 0u); }

// VPL j of the frame.
Vpl ml_vpl(uint j) {
  GpuVpl v = ml_vpls[j];
  return Vpl(v.position, v.normal, v.intensity);
}

// shade_vpl(frame, point, vpl, &shadow_rays) of exhaustive_sampler.h.
vec3 shade_vpl(ShadingPoint sp, Vpl vpl, inout uint shadow_rays) {
  return shade_vpl(sp.p, sp.ng, sp.basis, sp.brdf, sp.wo, vpl, ml_params.clamp_distance, shadow_rays);
}

#include "gpu/shaders/indirect/exhaustive.glsl"
#include "gpu/shaders/indirect/uniform.glsl"
#include "gpu/shaders/indirect/slc.glsl"
#include "gpu/shaders/indirect/sst.glsl"
#include "gpu/shaders/indirect/rtslc.glsl"
#include "gpu/shaders/indirect/hybrid.glsl"

// IndirectSampler::estimate of the sampler ml_params.method names; ps continues the pixel
// sample's stream exactly where the CPU's ManyLightMethod hands it to estimate().
IndirectEstimate estimate_indirect(ShadingPoint sp, inout PixelSampler ps) {
  switch (ml_params.method) {
    case ML_METHOD_EXHAUSTIVE: return estimate_exhaustive(sp);
    case ML_METHOD_UNIFORM: return estimate_uniform(sp, ps);
    case ML_METHOD_SLC: return estimate_slc(sp, ps);
    case ML_METHOD_SST: return estimate_sst(sp, ps);
    case ML_METHOD_RTSLC: return estimate_rtslc(sp, ps);
    case ML_METHOD_HYBRID: return estimate_hybrid(sp, ps);
  }
  return indirect_estimate_zero();
}

#endif
