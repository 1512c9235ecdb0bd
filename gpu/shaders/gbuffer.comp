#version 460
#extension GL_GOOGLE_include_directive : require
// The first-hit pass (G-buffer): per pixel and sample, the camera ray of core/render/camera.cpp
// jittered by the pixel's Sobol sample (as the CPU's pixel loops do), traced through the flat BVH,
// turned into a Surface, and averaged into the AOVs the CPU's FrameOutput has (albedo, normal,
// depth) plus the emission the camera sees.
// Bindings: 0..4 the scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles, 7 GBufferTexel output.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/render/frame_layout.h"
SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
layout(std430, binding = 7) writeonly buffer GBuffer { GBufferTexel gbuffer[]; };
layout(push_constant) uniform Push { ViewParams view; };
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "gpu/shaders/ray_queries.glsl"
#include "core/rng/sobol_sampler.h"
#include "core/render/pinhole.h"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  if (xy.x >= view.width || xy.y >= view.height) return;
  uint pixel = xy.y * view.width + xy.x;
  vec3 albedo = vec3(0.0), normal = vec3(0.0), emission = vec3(0.0);
  float depth = 0.0;
  uint hits = 0u;
  for (uint i = 0u; i < view.spp; ++i) {
    PixelSampler ps = pixel_sampler(view.seed, pixel, view.sample_offset + i);
    vec2 jitter = pixel_sampler_get2d(ps);
    vec3 dir = camera_direction(view, float(xy.x) + jitter.x, float(xy.y) + jitter.y);
    BvhHit hit = ray_closest_hit(view.eye, dir);
    if (hit.triangle >= BVH_STACK_OVERFLOW) continue;  // a miss (or, never, an overflow)
    Surface s = make_surface(hit.triangle, vec2(hit.u, hit.v), dir);
    albedo += s.base_color;
    normal += s.ns;
    depth += hit.t * length(dir);
    emission += s.emission;
    ++hits;
  }
  float inv = 1.0 / float(view.spp);
  GBufferTexel texel;
  texel.albedo = albedo * inv;
  texel.depth = depth * inv;
  texel.normal = dot(normal, normal) > 0.0 ? normalize(normal) : normal;
  texel.hit_fraction = float(hits) * inv;
  texel.emission = emission * inv;
  texel.pad1 = 0.0;
  gbuffer[pixel] = texel;
}
