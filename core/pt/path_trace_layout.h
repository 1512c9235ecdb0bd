// The `pt` method's data crossing the host/GPU boundary (gpu/shaders/pt.comp and
// gpu/path_trace_pass.h), defined once for C++ (namespace sst::glsl, static_asserts) and GLSL:
// its push constants and the per-pixel sums it accumulates. The twin of the per-pixel state of
// PathTracer::render (core/pt/path_tracer.cpp).
#ifndef SST_CORE_PT_PATH_TRACE_LAYOUT_H
#define SST_CORE_PT_PATH_TRACE_LAYOUT_H

#include "core/render/frame_layout.h"

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
#endif

// Push constants of pt.comp: the frame (camera, seed, this dispatch's sample range), the ray
// offset of core/accel/ray_offset.h (EmbreeAccel's scene_ray_epsilon) and PathTracerParams.
struct PathTraceParams {
  ViewParams view;
  float ray_epsilon;
  int max_bounces;
  int rr_min_bounces;
  uint path_flags;  // RENDER_* (render_flags of core/render/render_options.h)
};

// Push constants of pt_wavefront.comp: one wave of camera paths, sample view.sample_offset of
// pixels first_pixel .. first_pixel + path_count - 1, path slot j holding pixel first_pixel + j.
struct PathWaveParams {
  PathTraceParams pt;
  uint first_pixel;
  uint path_count;
  uint pad0;
  uint pad1;
};

// What a wave's stages report to the host: the paths still live after a bounce (the host stops
// dispatching when none are), and whether a slot lay beyond the state buffer (its size per path
// is the shader compiler's; the host allocates kPathWaveStateBytes and checks this flag).
struct PathWaveStatus {
  uint live;
  uint overflow;
};

// One pixel's sums over the finite samples taken so far (the CPU's PathSample sum), and its
// counts (the CPU's RayCounters, per pixel: the host adds them up for exact frame totals).
struct PathTraceTexel {
  vec3 direct;
  float depth;
  vec3 indirect;
  uint samples;            // camera paths traced (finite or not)
  vec3 albedo;
  uint primary_rays;
  vec3 normal;
  uint shadow_rays;
  uint bounce_rays;
  uint nonfinite_samples;  // dropped for a NaN or Inf in direct or indirect
  uint pad0;
  uint pad1;
};

#ifdef __cplusplus
static_assert(sizeof(PathTraceParams) == 96);
static_assert(offsetof(PathTraceParams, ray_epsilon) == 80 && offsetof(PathTraceParams, path_flags) == 92);
static_assert(sizeof(PathTraceTexel) == 80);
static_assert(sizeof(PathWaveParams) == 112 && offsetof(PathWaveParams, first_pixel) == 96);
// Bytes the host allocates per PathState (core/pt/path_stages.h) in the GPU's std430 layout, which
// C++ cannot compute: about 460 today; the shader flags a state buffer too small for its slots.
constexpr size_t kPathWaveStateBytes = 640;
static_assert(offsetof(PathTraceTexel, indirect) == 16 && offsetof(PathTraceTexel, albedo) == 32);
static_assert(offsetof(PathTraceTexel, normal) == 48 && offsetof(PathTraceTexel, bounce_rays) == 64);
}  // namespace sst::glsl
#endif

#endif  // SST_CORE_PT_PATH_TRACE_LAYOUT_H
