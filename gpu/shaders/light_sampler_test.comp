#version 450
#extension GL_GOOGLE_include_directive : require
// Runs the light sampling (core/lights/light_sample.h through gpu/shaders/light_sampler.glsl) for a
// list of queries so that a test can compare it with the same source compiled as C++ and with the
// double-precision pick (tests/gpu/light_sampler_gpu_test.cpp).
// Bindings 0..4: the scene (GpuScene::buffers()); 5..10: the lights (GpuLights::buffers());
// 11: queries; 12: results. Push constant: the number of queries.
// Query i: 24 words, floats as their bits:
//   {p.xyz, tri, y.xyz, u_pick, ng.xyz, 0, u.xy, u_pos.xy, u_dir.xy, 0, 0, n.xyz, 0}
// Result i: 36 words, floats as their bits:
//   0 light_sample(p, n, u) returned true, 1..3 wi, 4 distance, 5..7 li, 8 pdf, 9 delta,
//   10..12 point, 13..15 normal,
//   16 light_pdf_emissive_hit(p, n, tri, y, ng),
//   17 light_sample_emission(u_pick, u_pos, u_dir) returned true, 18..20 position, 21..23 normal,
//   24..26 direction, 27..29 weight, 30 light,
//   31 light_pick(u_pick) index, 32 its remapped u,
//   33 light_pick_for(p, n, u_pick) index, 34 its pmf, 35 light_pick_pmf(p, n, that index).
#include "core/scene/scene_layout.h"
#include "core/lights/light_layout.h"
SCENE_BUFFERS(0)
LIGHT_BUFFERS(5)
#include "gpu/shaders/light_sampler.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 11) readonly buffer Queries { uint queries[]; };
layout(std430, binding = 12) writeonly buffer Results { uint results[]; };
layout(push_constant) uniform Push { uint count; };

float qf(uint o) { return uintBitsToFloat(queries[o]); }
vec3 q3(uint o) { return vec3(qf(o), qf(o + 1u), qf(o + 2u)); }

void put1(uint o, float v) { results[o] = floatBitsToUint(v); }
void put3(uint o, vec3 v) {
  put1(o, v.x);
  put1(o + 1u, v.y);
  put1(o + 2u, v.z);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  uint q = i * 24u, o = i * 36u;
  vec3 p = q3(q), y = q3(q + 4u), ng = q3(q + 8u), n = q3(q + 20u);
  uint tri = queries[q + 3u];
  float u_pick = qf(q + 7u);
  vec2 u = vec2(qf(q + 12u), qf(q + 13u)), u_pos = vec2(qf(q + 14u), qf(q + 15u)),
       u_dir = vec2(qf(q + 16u), qf(q + 17u));

  LightSample s;
  results[o] = light_sample(p, n, u, s) ? 1u : 0u;
  put3(o + 1u, s.wi);
  put1(o + 4u, s.distance);
  put3(o + 5u, s.li);
  put1(o + 8u, s.pdf);
  results[o + 9u] = s.delta ? 1u : 0u;
  put3(o + 10u, s.point);
  put3(o + 13u, s.normal);

  put1(o + 16u, light_pdf_emissive_hit(p, n, tri, y, ng));

  EmissionSample e;
  results[o + 17u] = light_sample_emission(u_pick, u_pos, u_dir, emission_focus_none(), e) ? 1u : 0u;
  put3(o + 18u, e.position);
  put3(o + 21u, e.normal);
  put3(o + 24u, e.direction);
  put3(o + 27u, e.weight);
  results[o + 30u] = e.light;

  float remapped = 0.0;
  uint index = light_header.distribution_size > 0u ? light_pick(u_pick, remapped) : 0u;
  results[o + 31u] = index;
  put1(o + 32u, remapped);
  float pick_pmf = 0.0;
  float pick_u = 0.0;
  uint picked = light_pick_for(p, n, u_pick, pick_pmf, pick_u);
  results[o + 33u] = picked;
  put1(o + 34u, pick_pmf);
  put1(o + 35u, picked == LIGHT_NONE ? 0.0 : light_pick_pmf(p, n, picked));
}
