#version 460
#extension GL_GOOGLE_include_directive : require
// rayquery build (gpu/CMakeLists.txt)
// The `pt` method on the GPU: the twin of PathTracer::render's pixel loop
// (core/pt/path_tracer.cpp). Per pixel and sample index: the camera ray jittered by the
// pixel's Sobol sample, one path (gpu/shaders/path_trace.glsl), non-finite samples dropped and
// counted, the rest summed in sample order into the pixel's PathTraceTexel. A frame is rendered in
// dispatches of consecutive sample indices [sample_offset, sample_offset + spp); the first
// (sample_offset 0) overwrites the texels, the rest add to them, so the sums are the CPU's, in
// the CPU's order. The host divides by the frame's spp (gpu/path_trace_pass.cpp).
// Bindings: 0..4 scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles, 7..12 lights
// (LIGHT_BUFFERS), 13 PathTraceTexel per pixel. Push constants: PathTraceParams.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/pt/path_trace_layout.h"
SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
LIGHT_BUFFERS(7)
layout(std430, binding = 13) buffer Texels { PathTraceTexel texels[]; };
layout(push_constant) uniform Push { PathTraceParams params; };
#define SCENE_RAY_EPSILON params.ray_epsilon
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "core/render/pinhole.h"
#include "gpu/shaders/path_trace.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  // One local copy of the view (its name too) keeps glslang's precise propagation small
  // (docs/design/one-source.md, the glslang pitfall).
  ViewParams pixel_view = params.view;
  if (xy.x >= pixel_view.width || xy.y >= pixel_view.height) return;
  uint pixel = xy.y * pixel_view.width + xy.x;
  PathTraceTexel acc = path_texel_empty();
  if (pixel_view.sample_offset != 0u) acc = texels[pixel];
  PathConfig cfg = path_config_for(params.max_bounces, params.rr_min_bounces, params.path_flags);
  for (uint i = 0u; i < pixel_view.spp; ++i) {
    PixelSampler ps = pixel_sampler(pixel_view.seed, pixel, pixel_view.sample_offset + i);
    vec3 dir = camera_sample_direction(pixel_view, xy.x, xy.y, ps);
    PathState st = path_begin(pixel_view.eye, dir, ps);
    trace_path_state(st, cfg);
    path_texel_add(acc, st.counters, st.result);
  }
  texels[pixel] = acc;
}
