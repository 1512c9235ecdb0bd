// The path tracer's path (core/pt/trace_path.h) on the GPU, over the scene and light buffers and
// the flat BVH (gpu/shaders/ray_queries.glsl). The including shader declares, before including
// this file: the scene buffers (SCENE_BUFFERS(first), core/scene/scene_layout.h), the light
// buffers (LIGHT_BUFFERS(first), core/lights/light_layout.h), and what ray_queries.glsl needs.
// The pixel sums below are the twin of PathTracer::render's (core/pt/path_tracer.cpp), for the
// shaders that trace `pt`'s paths: pt.comp (a path to its end) and pt_wavefront.comp (by stages).
#ifndef SST_GPU_SHADERS_PATH_TRACE_GLSL
#define SST_GPU_SHADERS_PATH_TRACE_GLSL
#include "gpu/shaders/light_sampler.glsl"
#include "gpu/shaders/ray_queries.glsl"
#include "core/pt/trace_path.h"
#include "core/pt/path_trace_layout.h"

// A pixel's sums before its first sample.
PathTraceTexel path_texel_empty() {
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

// A finished path's sample added to its pixel's sums, in sample order as the CPU adds them: its
// rays counted, and a NaN or Inf sample, a bug to find rather than a pixel to show, dropped and
// counted.
void path_texel_add(inout PathTraceTexel acc, PathCounters counters, PathSample p) {
  acc.primary_rays += counters.primary_rays;
  acc.shadow_rays += counters.shadow_rays;
  acc.bounce_rays += counters.bounce_rays;
  ++acc.samples;
  if (!is_finite3(p.direct) || !is_finite3(p.indirect)) {
    ++acc.nonfinite_samples;
    return;
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

#endif  // SST_GPU_SHADERS_PATH_TRACE_GLSL
