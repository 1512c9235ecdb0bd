#version 450
#extension GL_GOOGLE_include_directive : require
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
layout(std430, binding = 5) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, binding = 6) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };
LIGHT_BUFFERS(7)
layout(std430, binding = 13) buffer Texels { PathTraceTexel texels[]; };
layout(push_constant) uniform Push { PathTraceParams params; };
#define BVH_NODE(i) bvh_nodes[i]
#define BVH_TRIANGLE(i) bvh_triangles[i]
#define SCENE_RAY_EPSILON params.ray_epsilon
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "core/render/pinhole.h"
#include "gpu/shaders/path_trace.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

PathTraceTexel empty_texel() {
  PathTraceTexel t;
  t.direct = vec3(0.0);
  t.depth = 0.0;
  t.indirect = vec3(0.0);
  t.samples = 0u;
  t.albedo = vec3(0.0);
  t.primary_rays = 0u;
  t.normal = vec3(0.0);
  t.shadow_rays = 0u;
  t.bounce_rays = 0u;
  t.nonfinite_samples = 0u;
  t.pad0 = 0u;
  t.pad1 = 0u;
  return t;
}

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  // One local copy of the view (its name too) keeps glslang's precise propagation small
  // (docs/design/one-source.md, the glslang pitfall).
  ViewParams pixel_view = params.view;
  if (xy.x >= pixel_view.width || xy.y >= pixel_view.height) return;
  uint pixel = xy.y * pixel_view.width + xy.x;
  PathTraceTexel acc = empty_texel();
  if (pixel_view.sample_offset != 0u) acc = texels[pixel];
  for (uint i = 0u; i < pixel_view.spp; ++i) {
    PixelSampler ps = pixel_sampler(pixel_view.seed, pixel, pixel_view.sample_offset + i);
    vec2 jitter = pixel_sampler_get2d(ps);
    precise float px = float(xy.x) + jitter.x, py = float(xy.y) + jitter.y;
    vec3 dir = camera_direction(pixel_view, px, py);
    PathCounters counters = path_counters();
    Surface first_hit;
    bool hit;
    PathSample p = trace_path(pixel_view.eye, dir, params.max_bounces, params.rr_min_bounces, params.diffuse_only != 0u,
                              ps, counters, first_hit, hit);
    acc.primary_rays += counters.primary_rays;
    acc.shadow_rays += counters.shadow_rays;
    acc.bounce_rays += counters.bounce_rays;
    ++acc.samples;
    // A NaN or Inf sample is a bug to find, not a pixel to show: drop and count it (as the CPU).
    if (!is_finite3(p.direct) || !is_finite3(p.indirect)) {
      ++acc.nonfinite_samples;
      continue;
    }
    precise vec3 direct = acc.direct + p.direct;
    precise vec3 indirect = acc.indirect + p.indirect;
    precise vec3 albedo = acc.albedo + p.albedo;
    precise vec3 normal = acc.normal + p.normal;
    precise float depth = acc.depth + p.depth;
    acc.direct = direct;
    acc.indirect = indirect;
    acc.albedo = albedo;
    acc.normal = normal;
    acc.depth = depth;
  }
  texels[pixel] = acc;
}
