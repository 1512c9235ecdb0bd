#version 460
#extension GL_GOOGLE_include_directive : require
// rayquery build (gpu/CMakeLists.txt)
// The light paths of instant radiosity on the GPU: one invocation traces light path
// first_path + i (core/vpl/light_path.h, which the CPU runs too), its VPLs into its slots.
// gpu/vpl_generation_pass.cpp concatenates the paths in index order.
//
// Bindings: 0..4 the scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles,
//   7 VplSlot slots[]: path i's k-th deposit (k-th surface hit) at i * max_bounces + k,
//   8 uvec2 paths[]: path i's (deposits, closest-hit rays); deposits = kLightPathOverflow when
//     the BVH stack overflowed (never for a tree build_flat_bvh returned; the host throws),
//   9.. the lights (LIGHT_BUFFERS).
// VplSlot and the push constants: core/vpl/light_path_layout.h.
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"
#include "core/vpl/light_path_layout.h"

SCENE_BUFFERS(0)
#include "gpu/shaders/scene_accel.glsl"
layout(std430, binding = 7) writeonly buffer Slots { VplSlot slots[]; };
layout(std430, binding = 8) writeonly buffer Paths { uvec2 paths[]; };
LIGHT_BUFFERS(9)

layout(push_constant) uniform Push { VplGenerationPush params; };

#define SCENE_RAY_EPSILON params.ray_epsilon
// The scene kernels first: the traversal's alpha test (BVH_ALPHA_TEST) is one of them.
#include "gpu/shaders/surface.glsl"
#include "core/accel/bvh_traverse.h"
#include "gpu/shaders/light_sampler.glsl"
#include "gpu/shaders/ray_queries.glsl"

layout(local_size_x = 64) in;

void vpl_deposit(uint slot, vec3 position, vec3 normal, vec3 intensity) {
  VplSlot v;
  v.position = position;
  v.pad0 = 0.0;
  v.normal = normal;
  v.pad1 = 0.0;
  v.intensity = intensity;
  v.pad2 = 0.0;
  slots[slot] = v;
}

#define VPL_CTX_PARAM uint slot_base,
#define VPL_CTX slot_base,
#define VPL_DEPOSIT(deposit, hit, position, normal, intensity) vpl_deposit(slot_base + (deposit), position, normal, intensity)
#include "core/vpl/light_path.h"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.path_count) return;
  EmissionFocus focus;
  focus.center = params.focus_center;
  focus.radius = params.focus_radius;
  paths[i] = trace_light_path(i * params.max_bounces, params.seed, params.first_path + i, int(params.max_bounces),
                              int(params.min_bounces), params.diffuse_only != 0u, focus,
                              params.focus_bounces);
}
