// The per-pixel data of temporal reuse, defined once for C++ (namespace sst::glsl, static_asserts)
// and GLSL: what the current frame gives each pixel (TemporalInput), the history a pixel keeps
// from frame to frame (TemporalTexel) and the parameters of one accumulation (TemporalPush).
// Light is kept albedo-demodulated ("illumination": radiance / albedo), so that the history
// survives texture detail moving under it and the filters (core/filter) blur light, not texture.
#ifndef SST_CORE_TEMPORAL_TEMPORAL_LAYOUT_H
#define SST_CORE_TEMPORAL_TEMPORAL_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec2;
using glm::vec3;
using glm::vec4;
#endif

// One pixel of the current frame.
struct TemporalInput {
  vec3 direct;            // direct illumination (direct radiance / albedo)
  float depth;            // distance from the camera to the first hit; 0 for a miss
  vec3 indirect;          // indirect illumination (indirect radiance / albedo)
  float previous_depth;   // the same surface point's distance from the previous frame's camera (0: none)
  vec3 normal;            // first-hit shading normal
  float pad0;
  vec2 motion;            // where the pixel was in the previous frame, minus where it is now (pixels)
  vec2 pad1;
};

// One pixel's history after the current frame has been added.
struct TemporalTexel {
  vec3 direct;    // exponential averages of the illuminations
  float frames;   // frames in the averages (fractional where taps of different histories blend), <= cap
  vec3 indirect;
  float depth;    // the frame's depth and normal, against which the next frame tests its reprojection
  vec3 normal;
  float pad0;
  vec4 moments;   // averages of luminance and squared luminance: direct (x, y), indirect (z, w)
};

struct TemporalPush {
  uint width;
  uint height;
  float history_cap;      // the most frames an average holds: alpha = 1 / min(frames + 1, cap)
  float depth_tolerance;  // a history tap is kept when its depth is within this fraction of the expected
  float normal_cos;       // ... and the cosine between its normal and the current one is at least this
  uint pad0;
  uint pad1;
  uint pad2;
};

#ifdef __cplusplus
static_assert(sizeof(TemporalInput) == 64 && offsetof(TemporalInput, motion) == 48);
static_assert(sizeof(TemporalTexel) == 64 && offsetof(TemporalTexel, moments) == 48);
static_assert(sizeof(TemporalPush) == 32);
}  // namespace sst::glsl
namespace sst {
using glsl::TemporalInput;
using glsl::TemporalPush;
using glsl::TemporalTexel;
}  // namespace sst
#endif

#endif
