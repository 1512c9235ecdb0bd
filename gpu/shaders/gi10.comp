#version 460
#extension GL_GOOGLE_include_directive : require
// rayquery build (gpu/CMakeLists.txt)
// variants: GI10_SHADER_STAGE 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29
// GI-1.0 on the GPU: the stages of core/gi10/gi10_stages.h, one invocation per element, as the
// CPU's loops run them. Compiled once per stage (gi10_<GI10_STAGE_*>, gpu/CMakeLists.txt), SHADE
// twice more (GI10_SHADER_SHADE_*): in one pipeline for all, llvmpipe paid every stage's local
// arrays in each invocation (7 us each).
// Bindings: 0..4 scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles, 7..12 lights
// (LIGHT_BUFFERS), 13 the frame's Gi10Frame, 14..28 GI-1.0's buffers in the order of
// gpu/gi10_vulkan.cpp (pixels, emission, mask, radiance, sh, spawn, rays, hash, values, accum,
// denoise, aux, feedback, counters, output, ray reservoirs, slot reservoirs, slot surfaces): 32
// storage buffers, Mesa 22 lavapipe's limit per stage. Push constants: Gi10Push.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/gi10/gi10_layout.h"
#include "core/restir/restir_layout.h"
SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
LIGHT_BUFFERS(7)
layout(std430, binding = 13) readonly buffer FrameConstants { Gi10Frame gi_frame_constants; };
layout(std430, binding = 14) buffer Pixels { Gi10Pixel gi_pixels_buffer[]; };
layout(std430, binding = 15) buffer Emission { vec4 gi_emission_buffer[]; };
layout(std430, binding = 16) buffer Mask { uint gi_mask_buffer[]; };
layout(std430, binding = 17) buffer Radiance { vec4 gi_radiance_buffer[]; };
layout(std430, binding = 18) buffer Sh { vec4 gi_sh_buffer[]; };
layout(std430, binding = 19) buffer Spawn { uint gi_spawn_buffer[]; };
layout(std430, binding = 20) buffer Rays { Gi10Ray gi_rays_buffer[]; };
layout(std430, binding = 21) buffer Hash { uint gi_hash_buffer[]; };
layout(std430, binding = 22) buffer Values { vec4 gi_values_buffer[]; };
layout(std430, binding = 23) buffer Accum { uint gi_accum_buffer[]; };
layout(std430, binding = 24) buffer Denoise { vec4 gi_denoise_buffer[]; };
layout(std430, binding = 25) buffer Aux { vec4 gi_aux_buffer[]; };
layout(std430, binding = 26) buffer Feedback { vec4 gi_feedback_buffer[]; };
layout(std430, binding = 27) buffer Counters { uint gi_counters_buffer[]; };
layout(std430, binding = 28) buffer Output { vec4 gi_output_buffer[]; };
layout(std430, binding = 29) buffer RayReservoirs { RestirReservoir gi_ray_reservoirs_buffer[]; };
layout(std430, binding = 30) buffer SlotReservoirs { RestirReservoir gi_slot_reservoirs_buffer[]; };
layout(std430, binding = 31) buffer SlotSurfaces { RestirSurface gi_slot_surfaces_buffer[]; };
layout(push_constant) uniform Push { Gi10Push push; };
#define SCENE_RAY_EPSILON gi_frame_constants.scene_epsilon
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "gpu/shaders/light_sampler.glsl"
#include "gpu/shaders/ray_queries.glsl"

#define GI_CTX_PARAM
#define GI_CTX
#define GF gi_frame_constants
#define GI_PIXELS(i) gi_pixels_buffer[i]
#define GI_EMISSION(i) gi_emission_buffer[i]
#define GI_MASK(i) gi_mask_buffer[i]
#define GI_RADIANCE(i) gi_radiance_buffer[i]
#define GI_SH(i) gi_sh_buffer[i]
#define GI_SPAWN(i) gi_spawn_buffer[i]
#define GI_RAYS(i) gi_rays_buffer[i]
#define GI_HASH(i) gi_hash_buffer[i]
#define GI_VALUES(i) gi_values_buffer[i]
#define GI_ACCUM(i) gi_accum_buffer[i]
#define GI_DENOISE(i) gi_denoise_buffer[i]
#define GI_AUX(i) gi_aux_buffer[i]
#define GI_FEEDBACK(i) gi_feedback_buffer[i]
#define GI_COUNTERS(i) gi_counters_buffer[i]
#define GI_OUTPUT(i) gi_output_buffer[i]
#define GI_RAY_RESERVOIRS(i) gi_ray_reservoirs_buffer[i]
#define GI_SLOT_RESERVOIRS(i) gi_slot_reservoirs_buffer[i]
#define GI_SLOT_SURFACES(i) gi_slot_surfaces_buffer[i]
#define GI_ATOMIC_ADD(ref, v) atomicAdd(ref, v)
#define GI_ATOMIC_CAS(ref, compare, v) atomicCompSwap(ref, compare, v)
#define GI_ATOMIC_MIN(ref, v) atomicMin(ref, v)
#include "core/gi10/gi10_stages.h"

layout(local_size_x = 64) in;

void main() {
  // Dispatches wider than 65535 groups fold into rows of gl_NumWorkGroups.x groups.
  uint index = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x;
  if (index >= push.count) return;
  gi10_stage(GI10_SHADER_STAGE, push.pass, index);
}
