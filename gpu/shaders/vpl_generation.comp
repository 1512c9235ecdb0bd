#version 450
#extension GL_GOOGLE_include_directive : require
// The light paths of instant radiosity on the GPU: the GLSL twin of Tracer::trace in
// core/vpl/vpl_generator.cpp. One invocation traces light path first_path + i, a pure function of
// (seed, path index) through HashRng(seed, path, 0, kVplStream): the same draws in the same
// order as the CPU, the same deposits (intensity not yet divided by the path count), the same
// reasons to end a path. gpu/vpl_generation_pass.cpp concatenates the paths in index order.
//
// Bindings: 0..4 the scene (SCENE_BUFFERS), 5 BVH nodes, 6 BVH triangles,
//   7 VplSlot slots[]: path i's k-th deposit (k-th surface hit) at i * max_bounces + k,
//   8 uvec2 paths[]: path i's (deposits, closest-hit rays); deposits = VPL_PATH_OVERFLOW when
//     the BVH stack overflowed (never for a tree build_flat_bvh returned; the host throws),
//   9.. the lights (LIGHT_BUFFERS).
// VplSlot and the push constants are mirrored in gpu/vpl_generation_pass.cpp (static_asserts).
#include "core/scene/scene_layout.h"
#include "core/accel/bvh_layout.h"
#include "core/lights/light_layout.h"

// One deposit: position, normal (unit, on the side the light came from), intensity.
struct VplSlot {
  vec3 position;
  float pad0;
  vec3 normal;
  float pad1;
  vec3 intensity;
  float pad2;
};

SCENE_BUFFERS(0)
layout(std430, binding = 5) readonly buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, binding = 6) readonly buffer BvhTriangles { BvhTriangle bvh_triangles[]; };
layout(std430, binding = 7) writeonly buffer Slots { VplSlot slots[]; };
layout(std430, binding = 8) writeonly buffer Paths { uvec2 paths[]; };
LIGHT_BUFFERS(9)

layout(push_constant) uniform Push {
  uint seed;
  uint first_path;   // path index of invocation 0
  uint path_count;   // invocations that trace a path
  uint max_bounces;  // VplParams::vpl_max_bounces (slots per path)
  uint min_bounces;  // VplParams::vpl_min_bounces
  uint diffuse_only;
  float ray_epsilon;  // scene_ray_epsilon(scene)
  uint pad;
} params;

#define BVH_NODE(i) bvh_nodes[i]
#define BVH_TRIANGLE(i) bvh_triangles[i]
#define SCENE_RAY_EPSILON params.ray_epsilon
#include "core/accel/bvh_traverse.h"
#include "core/math/vector_math.h"
#include "core/rng/hash_rng.h"
#include "core/sampling/sampling.h"
#include "core/accel/ray_offset.h"
#include "gpu/shaders/surface.glsl"
#include "gpu/shaders/light_sampler.glsl"

// kVplStream of core/vpl/vpl_generator.h ("VPL1").
#define VPL_STREAM 0x56504C31u
#define VPL_PATH_OVERFLOW 0xFFFFFFFFu

layout(local_size_x = 64) in;

// The CPU writes `vec2 u(rng.next(), rng.next())`, whose two draws C++ leaves unordered; GCC,
// which builds sst, evaluates them right to left, so y takes the first draw and x the second.
vec2 next_2d_as_cpu(inout HashRng rng) {
  float y = hash_rng_next(rng);
  float x = hash_rng_next(rng);
  return vec2(x, y);
}

vec3 diffuse_albedo(Surface s) {
  precise vec3 a = (1.0 - s.metallic) * s.base_color;
  return params.diffuse_only != 0u ? s.base_color : a;
}

// Traces path `path`; writes its deposits from slot `base` on and returns (deposits, rays).
uvec2 trace(uint path, uint base) {
  HashRng rng = hash_rng(params.seed, path, 0u, VPL_STREAM);
  float u_pick = hash_rng_next(rng);
  vec2 u_pos = next_2d_as_cpu(rng);
  vec2 u_dir = next_2d_as_cpu(rng);
  EmissionSample e;
  if (!light_sample_emission(u_pick, u_pos, u_dir, e)) return uvec2(0u);
  vec3 origin = e.normal == vec3(0.0) ? e.position : offset_ray_origin(SCENE_RAY_EPSILON, e.position, e.normal);
  vec3 dir = e.direction;
  vec3 beta = e.weight;
  uint deposits = 0u, rays = 0u;
  for (uint hit_index = 0u; hit_index < params.max_bounces; ++hit_index) {
    ++rays;
    BvhHit hit = bvh_intersect(origin, dir, 0.0, kInf);
    if (hit.triangle == BVH_STACK_OVERFLOW) return uvec2(VPL_PATH_OVERFLOW, rays);
    if (hit.triangle == BVH_INVALID_TRIANGLE) break;
    Surface s = make_surface(hit.triangle, vec2(hit.u, hit.v), dir);
    vec3 albedo = diffuse_albedo(s);
    // Light arriving under the shading hemisphere is not reflected: the path tracer's rule.
    if (!(dot3(dir, s.ns) < 0.0) || !(max_component(albedo) > 0.0)) break;
    precise vec3 intensity = beta * albedo * kInvPi;
    if (!is_finite3(intensity)) break;
    VplSlot slot;
    slot.position = s.p;
    slot.pad0 = 0.0;
    slot.normal = s.ns;
    slot.pad1 = 0.0;
    slot.intensity = intensity;
    slot.pad2 = 0.0;
    slots[base + deposits] = slot;
    ++deposits;
    if (hit_index + 1u >= params.max_bounces) break;

    vec2 u_bounce = next_2d_as_cpu(rng);
    float u_roulette = hash_rng_next(rng);
    if (hit_index + 1u >= params.min_bounces) {
      float survive = min(1.0, max_component(albedo));
      if (u_roulette >= survive) break;
      precise vec3 b = beta / survive;
      beta = b;
    }
    // Cosine-weighted about the shading normal: f cos / pdf = albedo.
    vec3 wi = to_world(basis_from_normal(s.ns), sample_cosine_hemisphere(u_bounce.x, u_bounce.y));
    if (!(dot3(wi, s.ng) > 0.0)) break;  // would pass through the surface
    precise vec3 b = beta * albedo;
    beta = b;
    origin = offset_ray_origin(SCENE_RAY_EPSILON, s.p, s.ng);
    dir = wi;
  }
  return uvec2(deposits, rays);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.path_count) return;
  paths[i] = trace(params.first_path + i, i * params.max_bounces);
}
