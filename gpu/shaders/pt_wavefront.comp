#version 460
#extension GL_GOOGLE_include_directive : require
// rayquery build (gpu/CMakeLists.txt)
// variants: PT_WAVE_STAGE 0 1 2 3 4
// The `pt` method on the GPU as a wavefront: the stages of core/pt/path_stages.h, each a dispatch
// over a wave of path states kept in a buffer, instead of pt.comp's one invocation per path to its
// end. Compiled once per stage (pt_wavefront_<PT_WAVE_STAGE>): 0 the camera ray and its hit
// (path_begin, path_first_hit), 1 path_shade, 2 the shadow ray and path_shadow_result, 3 the bounce
// ray and path_bounce_hit (counting the paths still live), 4 the wave's samples added to the
// pixels' sums in pt.comp's order, so the images are the same bits. gpu/path_trace_pass.cpp runs
// the waves: for each sample index, for each range of pixels, 0, then (1, 2, 3) while paths live,
// then 4.
// Bindings: 0..4 scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles, 7..12 lights
// (LIGHT_BUFFERS), 13 PathTraceTexel per pixel, 14 PathState per slot, 15 PathWaveStatus.
// Push constants: PathWaveParams.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/pt/path_trace_layout.h"
SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
LIGHT_BUFFERS(7)
layout(std430, binding = 13) buffer Texels { PathTraceTexel texels[]; };
layout(push_constant) uniform Push { PathWaveParams wave; };
#define SCENE_RAY_EPSILON wave.pt.ray_epsilon
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "core/render/pinhole.h"
#include "gpu/shaders/path_trace.glsl"
layout(std430, binding = 14) buffer States { PathState states[]; };
layout(std430, binding = 15) buffer Status { PathWaveStatus status; };

layout(local_size_x = 64) in;

void main() {
  uint slot = gl_GlobalInvocationID.x;
  if (slot >= wave.path_count) return;
  if (slot >= uint(states.length())) {
    atomicOr(status.overflow, 1u);
    return;
  }
  PathConfig cfg = path_config_for(wave.pt.max_bounces, wave.pt.rr_min_bounces, wave.pt.path_flags);
  uint pixel = wave.first_pixel + slot;
#if PT_WAVE_STAGE == 0
  // One local copy of the view keeps glslang's precise propagation small (as pt.comp).
  ViewParams pixel_view = wave.pt.view;
  PixelSampler ps = pixel_sampler(pixel_view.seed, pixel, pixel_view.sample_offset);
  vec3 dir = camera_sample_direction(pixel_view, pixel % pixel_view.width, pixel / pixel_view.width, ps);
  PathState st = path_begin(pixel_view.eye, dir, ps);
  BvhHit h;
  ray_closest_hit_into(st.origin, st.dir, h);
  path_first_hit(st, h, cfg);
  states[slot] = st;
#elif PT_WAVE_STAGE == 1
  PathState st = states[slot];
  if ((st.flags & PATH_ACTIVE) == 0u) return;
  path_shade(st, cfg);
  states[slot] = st;
#elif PT_WAVE_STAGE == 2
  PathState st = states[slot];
  if ((st.flags & PATH_NEE) == 0u) return;
  bool occluded = false;
  if ((st.flags & PATH_RAY_SHADOW) != 0u) occluded = RAY_OCCLUDED(st.shadow.origin, st.shadow.dir, st.shadow.tmax);
  path_shadow_result(st, occluded);
  states[slot] = st;
#elif PT_WAVE_STAGE == 3
  PathState st = states[slot];
  if ((st.flags & PATH_RAY_BOUNCE) == 0u) return;
  BvhHit h;
  ray_closest_hit_into(st.origin, st.dir, h);
  path_bounce_hit(st, h, cfg);
  if ((st.flags & PATH_ACTIVE) != 0u) atomicAdd(status.live, 1u);
  states[slot] = st;
#else
  PathState st = states[slot];
  PathTraceTexel acc = path_texel_empty();
  if (wave.pt.view.sample_offset != 0u) acc = texels[pixel];
  path_texel_add(acc, st.counters, st.result);
  texels[pixel] = acc;
#endif
}
