#version 450
#extension GL_GOOGLE_include_directive : require
// Evaluates make_surface (core/shading/surface_eval.h through gpu/shaders/surface.glsl) for a list
// of hits so that a test can compare it with the same source compiled as C++
// (tests/gpu/scene_upload_test.cpp).
// Bindings 0..4: the scene (sst::gpu::GpuScene::buffers()); 5: queries; 6: results.
// Query i: 8 words {triangle, bits(b1), bits(b2), 0, bits(incoming.xyz), 0}.
// Result i: 24 words {p.xyz, front_face, ng.xyz, material, ns.xyz, triangle, uv.xy, metallic,
// roughness, base_color.xyz, 0, emission.xyz, 0}, floats as their bits.
#include "core/scene/scene_layout.h"
SCENE_BUFFERS(0)
#include "gpu/shaders/surface.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 5) readonly buffer Queries { uint queries[]; };
layout(std430, binding = 6) writeonly buffer Results { uint results[]; };
layout(push_constant) uniform Push { uint count; };

void put3(uint o, vec3 v) {
  results[o] = floatBitsToUint(v.x);
  results[o + 1u] = floatBitsToUint(v.y);
  results[o + 2u] = floatBitsToUint(v.z);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  uint q = i * 8u;
  uint tri = queries[q];
  vec2 b = vec2(uintBitsToFloat(queries[q + 1u]), uintBitsToFloat(queries[q + 2u]));
  vec3 incoming = vec3(uintBitsToFloat(queries[q + 4u]), uintBitsToFloat(queries[q + 5u]),
                       uintBitsToFloat(queries[q + 6u]));
  Surface s = make_surface(tri, b, incoming);
  uint o = i * 24u;
  put3(o, s.p);
  results[o + 3u] = s.front_face ? 1u : 0u;
  put3(o + 4u, s.ng);
  results[o + 7u] = s.material;
  put3(o + 8u, s.ns);
  results[o + 11u] = s.triangle;
  results[o + 12u] = floatBitsToUint(s.uv.x);
  results[o + 13u] = floatBitsToUint(s.uv.y);
  results[o + 14u] = floatBitsToUint(s.metallic);
  results[o + 15u] = floatBitsToUint(s.roughness);
  put3(o + 16u, s.base_color);
  results[o + 19u] = 0u;
  put3(o + 20u, s.emission);
  results[o + 23u] = 0u;
}
