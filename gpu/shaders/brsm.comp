#version 460
#extension GL_GOOGLE_include_directive : require
// rayquery build (gpu/CMakeLists.txt)
// BRSM VPL generation on the GPU: one stage per dispatch (BrsmPush::stage), each invocation one
// element of it (brsm_stage_step, core/brsm/brsm.h, which the CPU runs too), in the order of
// brsm_schedule (gpu/brsm_pass.cpp).
//
// Bindings: 0..4 the scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles,
//   7 BrsmSettings settings (one), 8 BrsmMap maps[], 9 BrsmGSample gbuffer[],
//   10 BrsmTexel texels[] (the current map's), 11 vec2 mip[] (its chain),
//   12 Vpl vpls[] (every map's draws, at map.vpl_offset + point; std430 lays Vpl out as VplSlot),
//   13.. the lights (LIGHT_BUFFERS).
// The layouts: core/brsm/brsm_layout.h, core/vpl/vpl.h.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/brsm/brsm_layout.h"
#include "core/vpl/vpl.h"

SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
layout(std430, binding = 7) readonly buffer Settings { BrsmSettings settings; };
layout(std430, binding = 8) readonly buffer Maps { BrsmMap maps[]; };
layout(std430, binding = 9) buffer GBuffer { BrsmGSample gbuffer[]; };
layout(std430, binding = 10) buffer Texels { BrsmTexel texels[]; };
layout(std430, binding = 11) buffer Mip { vec2 mip[]; };
layout(std430, binding = 12) writeonly buffer Vpls { Vpl vpls[]; };
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
#define BRSM_STORE_GSAMPLE(i, g) gbuffer[i] = g
#define BRSM_STORE_TEXEL(i, t) texels[i] = t
#define BRSM_STORE_MIP(i, m) mip[i] = m
#define BRSM_STORE_VPL(i, v) vpls[i] = v
#include "core/brsm/brsm.h"

layout(local_size_x = 64) in;

void main() {
  // Large stages come as several rows of workgroups (gpu/brsm_pass.cpp), numbered row by row.
  uint i = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x;
  brsm_stage_step(settings, maps[push.map_index], push.map_index, push.stage, push.level, i);
}
