#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// rayquery build (gpu/CMakeLists.txt)
// The sampling stage of every VPL method on the GPU: the twin of the pixel loop of
// core/manylight/many_light_method.cpp. Per pixel and sample: the jittered camera ray, the direct
// light exactly as `pt` with max_bounces = 0 computes it (path_trace.glsl; or rtslc's own from
// its cuts of the emitter tree, core/manylight/rtslc/rtslc_direct.h), then one indirect
// estimate from the frame's sampler at the first hit (indirect_sampler.glsl), summed into the
// pixel's ManyLightTexel. A frame is rendered in dispatches of consecutive sample indices
// [sample_offset, sample_offset + spp); the first overwrites the texels, the rest add to them.
// On lavapipe an exhaustive sum may be split further into slices of VPLs (ManyLightPush).
// Bindings: 0..4 scene, 5..6 BVH, 7..12 lights, 13..19 the sampler's inputs (MANY_LIGHT_BUFFERS),
// 20 the texels, 21 the dispatch's words (ML_DISPATCH_*: the traversal-depth histogram, 65 bins,
// the last one "64 or more", then its counters), 22 and 23 the slices' running sums in and out.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/manylight/many_light_layout.h"
#include "core/render/frame_layout.h"
SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
LIGHT_BUFFERS(7)
MANY_LIGHT_BUFFERS(13)
layout(std430, binding = 20) buffer Texels { ManyLightTexel texels[]; };
layout(std430, binding = 21) buffer DispatchWords { uint dispatch_words[]; };
// Two buffers, swapped after each slice: reading and writing one buffer would make glslang's
// `precise` propagation cycle through it and exhaust memory.
layout(std430, binding = 22) readonly buffer SlicesIn { ManyLightSlice slices_in[]; };
layout(std430, binding = 23) writeonly buffer SlicesOut { ManyLightSlice slices_out[]; };
layout(push_constant) uniform Push { ManyLightPush push; };
#define SCENE_RAY_EPSILON push.scene_epsilon
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "core/rng/sobol_sampler.h"
#include "core/render/pinhole.h"
#include "gpu/shaders/path_trace.glsl"
#include "gpu/shaders/indirect_sampler.glsl"
#include "core/manylight/rtslc/rtslc_direct.h"
#include "core/manylight/direct_pass.h"
#include "core/manylight/shading_point.h"

layout(local_size_x = 8, local_size_y = 8) in;

ManyLightTexel empty_texel() {
  ManyLightTexel t;
  t.direct = vec3(0.0);
  t.depth = 0.0;
  t.indirect = vec3(0.0);
  t.samples = 0u;
  t.indirect2 = vec3(0.0);
  t.indirect_samples = 0u;
  t.albedo = vec3(0.0);
  t.nodes = 0u;
  t.normal = vec3(0.0);
  t.shadow_rays = 0u;
  t.primary_rays = 0u;
  t.bounce_rays = 0u;
  t.nonfinite = 0u;
  t.loop_budget_hits = 0u;
  return t;
}

void main() {
  uvec2 xy = gl_GlobalInvocationID.xy;
  if (xy.x >= push.view.width || xy.y >= push.view.height) return;
  uint pixel = xy.y * push.view.width + xy.x;
  bool first_slice = (push.slice_flags & ML_SLICE_FIRST) != 0u;
  bool last_slice = (push.slice_flags & ML_SLICE_LAST) != 0u;
  ManyLightTexel acc = empty_texel();
  if (push.view.sample_offset != 0u || !first_slice) acc = texels[pixel];
  bool diffuse_only = (push.path_flags & RENDER_DIFFUSE_ONLY) != 0u;
  for (uint k = 0u; k < push.view.spp; ++k) {
    PixelSampler ps = pixel_sampler(push.view.seed, pixel, push.view.sample_offset + k);
    vec3 dir = camera_sample_direction(push.view, xy.x, xy.y, ps);
    PathCounters counters = path_counters();
    Surface hit;
    bool has_hit;
    // rtslc with direct_light = cuts samples the direct light itself (rtslc_direct.h).
    // ReSTIR DI (RENDER_RESTIR_DIRECT) takes its place, as every method's direct light.
    bool restir = (push.path_flags & RENDER_RESTIR_DIRECT) != 0u;
    bool own_direct =
        !restir && (kSpecOwnDirect != kSpecUnset ? kSpecOwnDirect != 0u : ml_params.rtslc_direct_cut_max_size != 0u);
    PathConfig cfg = many_light_direct_config(own_direct || restir, diffuse_only, push.compensation_max_bounces,
                                              push.compensation_rr_min_bounces, ml_params.clamp_distance,
                                              ml_params.clamp_per_depth);
    PathSample d = trace_path(push.view.eye, dir, cfg, ps, counters, hit, has_hit);
    if (own_direct && d.depth > 0.0)
      d.direct += estimate_rtslc_direct(shading_point(hit, dir, d.depth, diffuse_only, int(xy.x), int(xy.y)),
                                        ps, counters);
    // Every slice retraces the camera ray (the same bits each time); the first one counts it.
    if (first_slice) {
      acc.primary_rays += counters.primary_rays;
      acc.shadow_rays += counters.shadow_rays;
      acc.bounce_rays += counters.bounce_rays;
      ++acc.samples;
    }
    vec3 value = vec3(0.0);
    if (d.depth > 0.0) {
      ShadingPoint sp = shading_point(hit, dir, d.depth, diffuse_only, int(xy.x), int(xy.y));
      IndirectEstimate e;
      if (first_slice && last_slice) {
        e = estimate_indirect(sp, ps);
      } else {
        vec3 sum = first_slice ? vec3(0.0) : slices_in[pixel].sum;
        e = estimate_exhaustive_range(sp, push.vpl_first, push.vpl_end, sum);
        if (!last_slice) slices_out[pixel].sum = e.value;
      }
      acc.shadow_rays += e.shadow_rays;
      if (last_slice) {
        acc.nodes += e.nodes_visited;
        ++acc.indirect_samples;
        atomicAdd(dispatch_words[min(e.nodes_visited, 64u)], 1u);
        // The compensation path's light (zero without clamp compensation) is part of the estimate.
        value = e.value + d.indirect;
      }
    }
    // The lanes of a subgroup share lavapipe's loop limit, and the subgroup's iterations are at
    // most the sum of its lanes': over the budget by that bound, the sample may be cut short.
    uint group_iterations = subgroupAdd(bvh_loop_iterations);
    if (subgroupElect()) atomicMax(dispatch_words[ML_DISPATCH_MAX_ITERATIONS], group_iterations);
    if (group_iterations > BVH_LAVAPIPE_LOOP_BUDGET) {
      ++acc.loop_budget_hits;
      atomicAdd(dispatch_words[ML_DISPATCH_BUDGET_HITS], 1u);
    }
    if (!last_slice) continue;
    if (!is_finite3(d.direct) || !is_finite3(value)) {
      ++acc.nonfinite;
      continue;
    }
    precise vec3 direct = acc.direct + d.direct;
    precise vec3 indirect = acc.indirect + value;
    precise vec3 indirect2 = acc.indirect2 + value * value;
    precise vec3 albedo = acc.albedo + d.albedo;
    precise vec3 normal = acc.normal + d.normal;
    precise float depth = acc.depth + d.depth;
    acc.direct = direct;
    acc.indirect = indirect;
    acc.indirect2 = indirect2;
    acc.albedo = albedo;
    acc.normal = normal;
    acc.depth = depth;
  }
  texels[pixel] = acc;
}
