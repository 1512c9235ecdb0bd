#version 460
#extension GL_GOOGLE_include_directive : require
// rayquery build (gpu/CMakeLists.txt)
// variants: RESTIR_STAGE 0 1 2 3 4 5
// ReSTIR DI and ReSTIR GI on the GPU: the passes of core/restir/restir_stages.h and the initial
// passes of restir_di_stages.h and restir_gi_stages.h, one dispatch each over the image, the twin
// of run_restir's loops (core/restir/restir.cpp). Compiled once per stage (restir_<RESTIR_STAGE>):
// 0 the camera ray, its first hit and ReSTIR DI's initial reservoir; 1 the temporal pass; 2 a
// spatial pass; 3 the round's estimate added to the pixel's sums; 4 as 0, ReSTIR GI's; 5 ReSTIR
// GI's history validated after the scene moved (read from 18, written to 15).
// gpu/restir_pass.cpp runs a frame: for each round 0 or 4, 5 where the history is posed anew, 1
// where there is history, 2 per spatial pass (the reservoir buffers swapping after each), then 3.
// Bindings: 0..4 scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles, 7..12 lights
// (LIGHT_BUFFERS), 13 RestirSurface per pixel, 14 the reservoirs read, 15 the reservoirs written,
// 16 RestirTexel per pixel, 17 and 18 the previous round's surfaces and reservoirs, 19 its view.
// Push constants: RestirPush.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/restir/restir_layout.h"
SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
LIGHT_BUFFERS(7)
layout(std430, binding = 13) buffer Surfaces { RestirSurface surfaces[]; };
layout(std430, binding = 14) readonly buffer ReservoirsIn { RestirReservoir reservoirs_in[]; };
layout(std430, binding = 15) writeonly buffer ReservoirsOut { RestirReservoir reservoirs_out[]; };
layout(std430, binding = 16) buffer Texels { RestirTexel texels[]; };
layout(std430, binding = 17) readonly buffer HistorySurfaces { RestirSurface history_surfaces[]; };
layout(std430, binding = 18) readonly buffer HistoryReservoirs { RestirReservoir history_reservoirs[]; };
layout(std430, binding = 19) readonly buffer HistoryView { ViewParams history_view; };
layout(push_constant) uniform Push { RestirPush push; };
#define SCENE_RAY_EPSILON push.ray_epsilon
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "gpu/shaders/path_trace.glsl"
#define RESTIR_CTX_PARAM
#define RESTIR_CTX
#define RESTIR_SURFACE(i) surfaces[i]
#define RESTIR_RESERVOIR(i) reservoirs_in[i]
#define RESTIR_HISTORY_SURFACE(i) history_surfaces[i]
#define RESTIR_HISTORY_RESERVOIR(i) history_reservoirs[i]
#include "core/restir/restir_stages.h"
#include "core/restir/restir_di_stages.h"
#include "core/restir/restir_gi_stages.h"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  RestirPush round_push = push;
  if (xy.x >= round_push.view.width || xy.y >= round_push.view.height) return;
  uint pixel = xy.y * round_push.view.width + xy.x;
  PathCounters c = path_counters();
#if RESTIR_STAGE == 0 || RESTIR_STAGE == 4
  // (Not a ?: of the two: glslang would select between the buffer's struct type and the plain one.)
  RestirTexel t = restir_texel_empty();
  if (round_push.view.sample_offset != 0u) t = texels[pixel];
  RestirSurface s;
#if RESTIR_STAGE == 0
  reservoirs_out[pixel] = restir_di_initial_pixel(round_push, xy.x, xy.y, s, c);
#else
  reservoirs_out[pixel] = restir_gi_initial_pixel(round_push, xy.x, xy.y, s, c);
#endif
  surfaces[pixel] = s;
#elif RESTIR_STAGE == 1
  reservoirs_out[pixel] = restir_temporal_pixel(round_push, xy.x, xy.y, history_view, c);
  RestirTexel t = texels[pixel];
#elif RESTIR_STAGE == 2
  reservoirs_out[pixel] = restir_spatial_pixel(round_push, xy.x, xy.y, c);
  RestirTexel t = texels[pixel];
#elif RESTIR_STAGE == 5
  reservoirs_out[pixel] = restir_gi_validate_pixel(round_push, xy.x, xy.y, c);
  RestirTexel t = texels[pixel];
#else
  RestirTexel t = texels[pixel];
  restir_texel_add(t, restir_shade(surfaces[pixel], (round_push.flags & RESTIR_DIFFUSE_ONLY) != 0u, reservoirs_in[pixel]));
#endif
  restir_texel_count(t, c);
  texels[pixel] = t;
}
