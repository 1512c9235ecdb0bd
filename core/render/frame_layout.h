// Per-frame data crossing the host/GPU boundary, defined once for C++ (namespace sst::glsl,
// static_asserts) and GLSL: the view a dispatch renders (ViewParams, push constants filled from
// core/render/camera.h's PinholeCamera basis so that both backends generate the same rays) and
// the per-pixel outputs of the first-hit (G-buffer) and many-light sampling passes.
#ifndef SST_CORE_RENDER_FRAME_LAYOUT_H
#define SST_CORE_RENDER_FRAME_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
#endif

// The path flags of the GPU passes that trace camera paths (PathTraceParams, ManyLightPush): what
// of RenderOptions their paths read (render_flags, core/render/render_options.h).
#define RENDER_DIFFUSE_ONLY 1u   // diffuse_only: every material Lambert
#define RENDER_RESTIR_DIRECT 2u  // direct_sampler restir: the first hit's direct light comes from ReSTIR DI

// What one dispatch renders: the camera, the image size, the seed and its range of sample indices.
struct ViewParams {
  vec3 eye;
  float tan_half_y;  // tan(yfov / 2)
  vec3 right;        // unit camera basis, right-handed: right x up = -forward
  float aspect;      // width / height of the image
  vec3 up;
  uint width;
  vec3 forward;
  uint height;
  uint seed;         // RenderOptions::seed
  uint spp;
  uint sample_offset;  // first sample index of this dispatch (large renders are split)
  uint pad0;
};

// The first-hit AOVs of one pixel, averaged over its samples as the CPU's FrameOutput has them:
// base colour, shading normal (normalised sum; 0 where nothing was hit), distance to the hit
// (0 for a miss), emission seen by the camera.
struct GBufferTexel {
  vec3 albedo;
  float depth;
  vec3 normal;
  float hit_fraction;  // samples that hit something / spp
  vec3 emission;
  float pad1;
};

// One pixel of the many-light sampling pass (gpu/shaders/many_light.comp): the sums the CPU's
// ManyLightMethod keeps per pixel, accumulated over the samples of every dispatch (the first
// dispatch of a frame overwrites), and per-pixel counts whose totals are the frame's counters.
struct ManyLightTexel {
  vec3 direct;            // sum of the direct light (emission seen + next-event estimation)
  float depth;            // sum of the first-hit distances
  vec3 indirect;          // sum of the indirect estimates
  uint samples;           // camera samples taken
  vec3 indirect2;         // sum of their squares (for the variance of the pixel mean)
  uint indirect_samples;  // samples that hit a surface and drew an indirect estimate
  vec3 albedo;            // sum of the first-hit base colours
  uint nodes;             // tree nodes visited by the indirect estimates, summed
  vec3 normal;            // sum of the first-hit shading normals
  uint shadow_rays;       // of the direct light and of the indirect estimates
  uint primary_rays;
  uint bounce_rays;       // the direct light's BSDF-sampled ray (for MIS with emitters it hits)
  uint nonfinite;         // samples dropped for a NaN or Inf
  uint loop_budget_hits;  // samples after which the invocation was past BVH_LAVAPIPE_LOOP_BUDGET
};

// The push constants of one dispatch of the many-light sampling pass. An exhaustive sum over more
// VPLs than lavapipe's loop limit lets one invocation shade is split into slices of VPLs
// [vpl_first, vpl_end), one dispatch each, every slice continuing the previous slice's sum
// (ManyLightSlice) for the same pixel sample: the first slice also takes the camera ray's direct
// light and counts, the last one adds the finished estimate to the pixel's sums.
#define ML_SLICE_FIRST 1u
#define ML_SLICE_LAST 2u
struct ManyLightPush {
  ViewParams view;
  float scene_epsilon;  // SCENE_RAY_EPSILON of core/accel/ray_offset.h
  uint path_flags;      // RENDER_*
  uint vpl_first;       // the VPLs of this dispatch's slice (0, ~0u: all)
  uint vpl_end;
  uint slice_flags;     // ML_SLICE_FIRST | ML_SLICE_LAST; both for an unsliced dispatch
  // Clamp compensation of the direct pass (core/manylight/direct_pass.h): the compensating path's
  // bounces (0: none) and its Russian-roulette start.
  int compensation_max_bounces;
  int compensation_rr_min_bounces;
};

// The running sum of one pixel sample's exhaustive estimate between slices.
struct ManyLightSlice {
  vec3 sum;
  uint reserved;
};

// The many-light pass's counters of one dispatch (after the 65 bins of its traversal-depth
// histogram): how many pixel samples came near lavapipe's loop limit, and the most loop
// iterations a subgroup ran, from which the next slice is sized.
#define ML_DISPATCH_BUDGET_HITS 65u
#define ML_DISPATCH_MAX_ITERATIONS 66u
#define ML_DISPATCH_WORDS 67u

#ifdef __cplusplus
static_assert(sizeof(ManyLightPush) == 108 && offsetof(ManyLightPush, vpl_first) == 88);
static_assert(sizeof(ManyLightSlice) == 16);
static_assert(sizeof(ManyLightTexel) == 96);
static_assert(offsetof(ManyLightTexel, indirect) == 16 && offsetof(ManyLightTexel, indirect2) == 32);
static_assert(offsetof(ManyLightTexel, albedo) == 48 && offsetof(ManyLightTexel, normal) == 64);
static_assert(offsetof(ManyLightTexel, primary_rays) == 80);
static_assert(sizeof(GBufferTexel) == 48);
static_assert(offsetof(GBufferTexel, normal) == 16 && offsetof(GBufferTexel, emission) == 32);
static_assert(sizeof(ViewParams) == 80);
static_assert(offsetof(ViewParams, right) == 16 && offsetof(ViewParams, up) == 32);
static_assert(offsetof(ViewParams, forward) == 48 && offsetof(ViewParams, seed) == 64);
}  // namespace sst::glsl
#endif

#endif
