// The per-pixel data of temporal reuse, defined once for C++ (namespace sst::glsl, static_asserts)
// and GLSL: what the current frame gives each pixel (TemporalInput), the history a pixel keeps
// from frame to frame (TemporalTexel) and the parameters of one accumulation (TemporalPush).
// The history keeps radiance and the albedo of the same samples, averaged alike; their ratio is
// the illumination (radiance / albedo) that the filters (core/filter) blur, so that they blur
// light, not texture, and remodulating it by the averaged albedo gives back the averaged radiance
// exactly: under a static view the history is the plain mean of the frames. The albedo is the mean
// over the pixel's own samples, not the pixel centre's: radiance averaged over a pixel's footprint
// divided by the albedo of one point of it is wrong wherever texture varies inside the pixel, and
// under sub-pixel motion that error does not cancel when remodulating.
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
  vec3 direct;            // direct radiance
  float depth;            // distance from the camera to the first hit; 0 for a miss
  vec3 indirect;          // indirect radiance
  float previous_depth;   // the same surface point's distance from the previous frame's camera (0: none)
  vec3 normal;            // first-hit shading normal
  float normal_change;    // the largest distance between this normal and a 4-neighbour's (0 without hits)
  vec3 albedo;            // mean first-hit base colour of the pixel's samples
  float pad1;
  vec2 motion;            // where the pixel was in the previous frame, minus where it is now (pixels)
  vec2 luminance;         // luminance of the direct (x) and indirect (y) illumination, for the moments
};

// One pixel's history after the current frame has been added.
struct TemporalTexel {
  vec3 direct;    // exponential averages of the radiances
  float frames;   // frames in the averages (fractional where taps of different histories blend), <= cap
  vec3 indirect;
  float depth;    // the frame's depth and normal, against which the next frame tests its reprojection
  vec3 normal;
  float pad0;
  vec3 albedo;    // exponential average of the frames' albedo
  float pad1;
  vec4 moments;   // averages of illumination luminance and its square: direct (x, y), indirect (z, w)
};

struct TemporalPush {
  uint width;
  uint height;
  float history_cap;      // the most frames an average holds: alpha = 1 / min(frames + 1, cap)
  float depth_tolerance;  // a history tap is kept when its depth is within this fraction of the expected
  float normal_cos;       // ... and the cosine between its normal and the current one is at least this
                          // (the bound widened by TemporalInput::normal_change)
  uint pad0;
  uint pad1;
  uint pad2;
};

#ifdef __cplusplus
static_assert(sizeof(TemporalInput) == 80 && offsetof(TemporalInput, motion) == 64);
static_assert(sizeof(TemporalTexel) == 80 && offsetof(TemporalTexel, moments) == 64);
static_assert(sizeof(TemporalPush) == 32);
}  // namespace sst::glsl
namespace sst {
using glsl::TemporalInput;
using glsl::TemporalPush;
using glsl::TemporalTexel;
}  // namespace sst
#endif

#endif
