// ReSTIR's data crossing the host/GPU boundary (gpu/shaders/restir.comp, gpu/restir_pass.h),
// defined once for C++ (namespace sst::glsl, static_asserts) and GLSL: the push constants, a
// pixel's first hit, a pixel's reservoir and its output sums, for ReSTIR DI and ReSTIR GI alike.
// The CPU (core/restir/restir_di.cpp, restir_gi.cpp) keeps the same structs in host arrays, so
// both backends run one text.
#ifndef SST_CORE_RESTIR_RESTIR_LAYOUT_H
#define SST_CORE_RESTIR_RESTIR_LAYOUT_H

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

// RestirPush.flags.
#define RESTIR_DIFFUSE_ONLY 1u  // RenderOptions::diffuse_only
#define RESTIR_UNBIASED 2u      // restir_combine unbiased: neighbours' MIS weights checked by shadow rays
#define RESTIR_TEMPORAL 4u      // a temporal pass merges the history (restir_temporal, and there is history)
#define RESTIR_POSED 8u         // the scene moved since the history's round (restir_temporal evaluates it anew)

// Push constants of every stage: the view (its sample_offset is the round: each of a frame's spp
// rounds resamples the first hits of sample index `round` of every pixel), the reuse parameters,
// and the initial pass's: RestirDiParams' candidates (DI), RestirGiParams' path (GI). The previous
// round's view, which the temporal pass reprojects through, is a buffer of one ViewParams (push
// constants have 128 bytes).
struct RestirPush {
  ViewParams view;
  float ray_epsilon;          // SCENE_RAY_EPSILON of core/accel/ray_offset.h
  uint flags;                 // RESTIR_*
  uint light_candidates;      // DI: light samples per pixel
  uint brdf_candidates;       // DI: 0 or 1
  uint neighbours;
  float radius;               // pixels
  uint pass;                  // the spatial pass (its random stream)
  float temporal_cap;
  int max_bounces;            // GI: the secondary path's indirect bounces, counted from the pixel
  int rr_min_bounces;         // GI: bounces before Russian roulette, counted from the pixel
  uint pad0;
  uint pad1;
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

// RestirReservoir.light of a ReSTIR GI sample: a secondary vertex rather than a light.
#define RESTIR_GI_VERTEX 0xFFFFFFFEu

// A pixel's reservoir: its sample, the sample's contribution weight W (an estimate of 1 / its
// density, per unit area of the light or surface the sample lies on, per light for punctual ones),
// how many candidates it stands for (M), and the pixel's target function at the sample. The
// sample is a light's distribution entry and, on an emissive triangle, the point's barycentrics
// (ReSTIR DI); or a secondary vertex (light RESTIR_GI_VERTEX) with the radiance it sends toward
// the pixel that found it (ReSTIR GI), named also by its triangle and barycentrics so that it
// moves with its triangle when the scene is posed anew.
struct RestirReservoir {
  uint light;        // LIGHT_NONE: empty; RESTIR_GI_VERTEX: the vertex below
  float b1;          // the point's barycentrics on its triangle (an emissive triangle's or the vertex's)
  float b2;
  float weight;      // W
  float m;           // M
  float target;      // p^(y) at the pixel
  uint triangle;     // ReSTIR GI: the vertex's triangle
  uint pad1;
  vec3 point;        // ReSTIR GI: the secondary vertex
  float offset;      // its ray offset (Surface::offset)
  vec3 normal;       // its geometric normal, on the side the radiance leaves from
  float pad2;
  vec3 radiance;     // the radiance it sends toward the pixel's first hit (emission excluded)
  float pad3;
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
static_assert(sizeof(RestirPush) == 128 && offsetof(RestirPush, ray_epsilon) == 80);
static_assert(offsetof(RestirPush, pass) == 104);
static_assert(sizeof(RestirSurface) == 96 && offsetof(RestirSurface, base_color) == 48);
static_assert(offsetof(RestirSurface, hit) == 60 && offsetof(RestirSurface, dir) == 80);
static_assert(sizeof(RestirReservoir) == 80 && offsetof(RestirReservoir, target) == 20);
static_assert(offsetof(RestirReservoir, point) == 32 && offsetof(RestirReservoir, radiance) == 64);
static_assert(sizeof(RestirTexel) == 32 && offsetof(RestirTexel, nonfinite) == 24);
}  // namespace sst::glsl
namespace sst {
using glsl::RestirPush;
using glsl::RestirReservoir;
using glsl::RestirSurface;
using glsl::RestirTexel;
}  // namespace sst
#endif

#endif  // SST_CORE_RESTIR_RESTIR_LAYOUT_H
