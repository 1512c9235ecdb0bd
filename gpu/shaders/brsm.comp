#version 460
#extension GL_GOOGLE_include_directive : require
// rayquery build (gpu/CMakeLists.txt)
// BRSM VPL generation on the GPU: one stage per dispatch (BrsmPush::stage), each invocation one
// element of core/brsm/brsm.h's kernels, which the CPU runs too. gpu/brsm_pass.cpp runs the
// G-buffer once, then per map the texels, the filter, the mip levels one by one and the warp.
//
// Bindings: 0..4 the scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles,
//   7 BrsmSettings settings (one), 8 BrsmMap maps[], 9 BrsmGSample gbuffer[],
//   10 BrsmTexel texels[] (the current map's), 11 vec2 mip[] (its chain),
//   12 VplSlot vpls[] (every map's draws, at map.vpl_offset + point),
//   13.. the lights (LIGHT_BUFFERS).
// The layouts: core/brsm/brsm_layout.h, core/vpl/light_path_layout.h.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/brsm/brsm_layout.h"
#include "core/vpl/light_path_layout.h"

SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
layout(std430, binding = 7) readonly buffer Settings { BrsmSettings settings; };
layout(std430, binding = 8) readonly buffer Maps { BrsmMap maps[]; };
layout(std430, binding = 9) buffer GBuffer { BrsmGSample gbuffer[]; };
layout(std430, binding = 10) buffer Texels { BrsmTexel texels[]; };
layout(std430, binding = 11) buffer Mip { vec2 mip[]; };
layout(std430, binding = 12) writeonly buffer Vpls { VplSlot vpls[]; };
LIGHT_BUFFERS(13)

layout(push_constant) uniform Push { BrsmPush push; };

#define SCENE_RAY_EPSILON settings.ray_epsilon
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "gpu/shaders/light_sampler.glsl"
#include "gpu/shaders/ray_queries.glsl"

#define BRSM_CTX_PARAM
#define BRSM_CTX
#define BRSM_GSAMPLE(i) gbuffer[i]
#define BRSM_TEXEL(i) texels[i]
#define BRSM_MIP(i) mip[i]
#include "core/brsm/brsm.h"

layout(local_size_x = 64) in;

void main() {
  // Large stages come as several rows of workgroups (gpu/brsm_pass.cpp), numbered row by row.
  uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  BrsmSettings s = settings;
  uint res = s.resolution;
  if (push.stage == BRSM_STAGE_GBUFFER) {
    if (i >= s.gbuffer_width * s.gbuffer_height) return;
    gbuffer[i] = brsm_gbuffer_sample(s, i % s.gbuffer_width, i / s.gbuffer_width);
  } else if (push.stage == BRSM_STAGE_TEXELS) {
    if (i >= res * res) return;
    texels[i] = brsm_texel(s, maps[push.map_index], push.map_index, i);
  } else if (push.stage == BRSM_STAGE_FILTER) {
    if (i >= res * res) return;
    mip[i] = brsm_filtered(s, i);
  } else if (push.stage == BRSM_STAGE_MIP) {
    uint side = res >> push.level;
    if (i >= side * side) return;
    mip[brsm_mip_offset(res, push.level) + i] = brsm_mip_sum(res, push.level, i);
  } else if (push.stage == BRSM_STAGE_WARP) {
    BrsmMap map = maps[push.map_index];
    if (i >= map.vpl_count) return;
    Vpl v = brsm_warp(s, map, push.map_index, i);
    VplSlot slot;
    slot.position = v.position;
    slot.pad0 = 0.0;
    slot.normal = v.normal;
    slot.pad1 = 0.0;
    slot.intensity = v.intensity;
    slot.pad2 = 0.0;
    vpls[map.vpl_offset + i] = slot;
  }
}
