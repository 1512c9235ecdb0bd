// ReSTIR DI's data crossing the host/GPU boundary (gpu/shaders/restir_di.comp and
// gpu/restir_di_pass.h), defined once for C++ (namespace sst::glsl, static_asserts) and GLSL: the
// push constants, a pixel's first hit, a pixel's reservoir and its output sums. The CPU
// (core/restir/restir_di.cpp) keeps the same structs in host arrays, so both run one text.
#ifndef SST_CORE_RESTIR_RESTIR_DI_LAYOUT_H
#define SST_CORE_RESTIR_RESTIR_DI_LAYOUT_H

#include "core/render/frame_layout.h"

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace sst::glsl {
using uint = uint32_t;
using glm::vec3;
#endif

// The most neighbours one spatial pass merges (RestirDiParams::neighbours).
#define RESTIR_MAX_NEIGHBOURS 16u

// RestirDiPush.flags.
#define RESTIR_DIFFUSE_ONLY 1u  // RenderOptions::diffuse_only
#define RESTIR_UNBIASED 2u      // restir_combine unbiased: neighbours' MIS weights checked by shadow rays
#define RESTIR_TEMPORAL 4u      // a temporal pass merges the history (restir_temporal, and there is history)

// Push constants of every stage: the view (its sample_offset is the round: each of a frame's spp
// rounds resamples the first hits of sample index `round` of every pixel) and RestirDiParams. The
// previous round's view, which the temporal pass reprojects through, is a buffer of one ViewParams
// (push constants have 128 bytes).
struct RestirDiPush {
  ViewParams view;
  float ray_epsilon;          // SCENE_RAY_EPSILON of core/accel/ray_offset.h
  uint flags;                 // RESTIR_*
  uint light_candidates;      // RestirDiParams::candidates
  uint brdf_candidates;       // 0 or 1
  uint neighbours;
  float radius;               // pixels
  uint pass;                  // the spatial pass (its random stream)
  float temporal_cap;         // RestirDiParams::temporal_cap
};

// The first hit of a pixel's camera ray in the current round: what the resampling evaluates a
// light sample at, for the pixel itself and for its neighbours.
struct RestirSurface {
  vec3 p;
  float offset;     // Surface::offset
  vec3 ng;          // geometric normal, on the viewer's side
  float metallic;
  vec3 ns;          // shading normal
  float roughness;
  vec3 base_color;
  uint hit;         // 0: the camera ray missed (no reservoir)
  vec3 lift;        // Surface::lift
  float depth;      // distance from the camera
  vec3 dir;         // the camera ray's unit direction
  float pad0;
};

// A pixel's reservoir: its sample (a light's distribution entry and, for a triangle, the
// barycentrics of the point), the sample's contribution weight W (an estimate of 1 / its density,
// per unit area of the light for triangles), how many candidates it stands for (M), and the
// pixel's target function at the sample.
struct RestirReservoir {
  uint light;        // LIGHT_NONE: empty
  float b1;
  float b2;
  float weight;      // W
  float m;           // M
  float target;      // p^(y) at the pixel
  uint pad0;
  uint pad1;
};

// A pixel's sums over a frame's rounds: the direct light and the rays traced.
struct RestirTexel {
  vec3 direct;
  uint primary_rays;
  uint shadow_rays;
  uint bounce_rays;
  uint nonfinite;     // rounds whose estimate was NaN or Inf (dropped)
  uint pad0;
};

#ifdef __cplusplus
static_assert(sizeof(RestirDiPush) == 112 && offsetof(RestirDiPush, ray_epsilon) == 80);
static_assert(offsetof(RestirDiPush, pass) == 104);
static_assert(sizeof(RestirSurface) == 96 && offsetof(RestirSurface, base_color) == 48);
static_assert(offsetof(RestirSurface, hit) == 60 && offsetof(RestirSurface, dir) == 80);
static_assert(sizeof(RestirReservoir) == 32 && offsetof(RestirReservoir, target) == 20);
static_assert(sizeof(RestirTexel) == 32 && offsetof(RestirTexel, nonfinite) == 24);
}  // namespace sst::glsl
namespace sst {
using glsl::RestirDiPush;
using glsl::RestirReservoir;
using glsl::RestirSurface;
using glsl::RestirTexel;
}  // namespace sst
#endif

#endif  // SST_CORE_RESTIR_RESTIR_DI_LAYOUT_H
