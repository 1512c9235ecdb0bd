// Per-frame data crossing the host/GPU boundary, defined once for C++ (namespace sst::glsl,
// static_asserts) and GLSL: the camera and frame parameters (push constants, filled from
// core/render/camera.h's PinholeCamera basis so that both backends generate the same rays) and
// the G-buffer texel the first-hit pass writes.
#ifndef SST_GPU_SHARED_FRAME_LAYOUT_H
#define SST_GPU_SHARED_FRAME_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
#endif

struct FrameParams {
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

#ifdef __cplusplus
static_assert(sizeof(GBufferTexel) == 48);
static_assert(offsetof(GBufferTexel, normal) == 16 && offsetof(GBufferTexel, emission) == 32);
static_assert(sizeof(FrameParams) == 80);
static_assert(offsetof(FrameParams, right) == 16 && offsetof(FrameParams, up) == 32);
static_assert(offsetof(FrameParams, forward) == 48 && offsetof(FrameParams, seed) == 64);
}  // namespace sst::glsl
#endif

#endif
