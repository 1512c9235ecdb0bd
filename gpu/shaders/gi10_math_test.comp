#version 450
#extension GL_GOOGLE_include_directive : require
// Runs GI-1.0's building blocks (core/gi10/gi10_math.h) on a list of inputs so that a test can
// compare them with the same source compiled as C++ (tests/gpu/gi10_math_gpu_test.cpp).
// Binding 0: inputs, 44 words each; binding 1: results, 64 words each; floats as their bits.
// Push constant: the number of inputs.
// Input i:
//   0..1 uv, 2..4 local direction d, 5..7 normal n, 8..10 eye, 11..13 x2, 14..16 ray direction w,
//   17 t, 18 k_hash, 19 min_cell, 20 base_exp (int), 21 short-ray bit, 22 l1, 23 l2,
//   24..27 cell value, 28..30 batch sum, 31 batch count k, 32 cap, 33 fixed-point value,
//   34..41 a key (level, tile.xyz, dir.xyz, short_ray), 42 a word to hash, 43 a frame index
// Result i:
//   0..2 gi_hemi_direction(uv), 3..4 gi_hemi_uv(d), 5 gi_texel_of_local(d),
//   6..14 gi_frame(n) (b1, b2, n), 15..22 gi_cell_address's key, 23..24 its offset,
//   25 its cell size, 26..27 bucket (4096) and checksum of that key, 28..29 of the input key,
//   30 pcg_hash(word), 31 gi_xx(word), 32 gi_hysteresis(l1, l2), 33..36 gi_cell_update,
//   37..38 gi_fixed_split (lo, hi), 39 gi_fixed_value of them, 40..41 gi_spawn_jitter(frame, 16),
//   42 gi_texel_of(frame of n, gi_texel_direction(frame of n, i & 63)), 43..45 that direction,
//   46..54 gi_sh_basis(0..8, d), 55 gi_cell_index(word % 4096, offset, i & 3), 56..63 0.
#include "core/gi10/gi10_math.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Inputs { uint inputs[]; };
layout(std430, binding = 1) writeonly buffer Results { uint results[]; };
layout(push_constant) uniform Push { uint count; };

float qf(uint o) { return uintBitsToFloat(inputs[o]); }
vec3 q3(uint o) { return vec3(qf(o), qf(o + 1u), qf(o + 2u)); }

void put1(uint o, float v) { results[o] = floatBitsToUint(v); }
void put3(uint o, vec3 v) {
  put1(o, v.x);
  put1(o + 1u, v.y);
  put1(o + 2u, v.z);
}
void put_key(uint o, GiCellKey k) {
  results[o] = k.level;
  results[o + 1u] = k.tile.x;
  results[o + 2u] = k.tile.y;
  results[o + 3u] = k.tile.z;
  results[o + 4u] = k.dir.x;
  results[o + 5u] = k.dir.y;
  results[o + 6u] = k.dir.z;
  results[o + 7u] = k.short_ray;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  uint q = i * 44u, o = i * 64u;

  put3(o, gi_hemi_direction(vec2(qf(q), qf(q + 1u))));
  vec3 d = q3(q + 2u);
  vec2 uv = gi_hemi_uv(d);
  put1(o + 3u, uv.x);
  put1(o + 4u, uv.y);
  results[o + 5u] = gi_texel_of_local(d);

  GiFrame f = gi_frame(q3(q + 5u));
  put3(o + 6u, f.b1);
  put3(o + 9u, f.b2);
  put3(o + 12u, f.n);

  GiCellAddress a = gi_cell_address(q3(q + 8u), q3(q + 11u), q3(q + 14u), qf(q + 17u), qf(q + 18u), qf(q + 19u),
                                    int(inputs[q + 20u]), inputs[q + 21u] != 0u);
  put_key(o + 15u, a.key);
  results[o + 23u] = a.offset.x;
  results[o + 24u] = a.offset.y;
  put1(o + 25u, a.cell_size);
  results[o + 26u] = gi_key_bucket(a.key, 4096u);
  results[o + 27u] = gi_key_checksum(a.key);

  GiCellKey key;
  key.level = inputs[q + 34u];
  key.tile = uvec3(inputs[q + 35u], inputs[q + 36u], inputs[q + 37u]);
  key.dir = uvec3(inputs[q + 38u], inputs[q + 39u], inputs[q + 40u]);
  key.short_ray = inputs[q + 41u];
  results[o + 28u] = gi_key_bucket(key, 4096u);
  results[o + 29u] = gi_key_checksum(key);
  uint word = inputs[q + 42u];
  results[o + 30u] = pcg_hash(word);
  results[o + 31u] = gi_xx(word);

  put1(o + 32u, gi_hysteresis(qf(q + 22u), qf(q + 23u)));
  vec4 value = gi_cell_update(vec4(qf(q + 24u), qf(q + 25u), qf(q + 26u), qf(q + 27u)), q3(q + 28u), qf(q + 31u),
                              qf(q + 32u));
  put1(o + 33u, value.x);
  put1(o + 34u, value.y);
  put1(o + 35u, value.z);
  put1(o + 36u, value.w);
  uvec2 s = gi_fixed_split(qf(q + 33u));
  results[o + 37u] = s.x;
  results[o + 38u] = s.y;
  put1(o + 39u, gi_fixed_value(s.x, s.y));
  uvec2 j = gi_spawn_jitter(inputs[q + 43u], 16u);
  results[o + 40u] = j.x;
  results[o + 41u] = j.y;

  vec3 w = gi_texel_direction(f, i & 63u);
  results[o + 42u] = gi_texel_of(f, w);
  put3(o + 43u, w);
  for (uint k = 0u; k < 9u; ++k) put1(o + 46u + k, gi_sh_basis(k, d));
  results[o + 55u] = gi_cell_index(word % 4096u, a.offset, i & 3u);
  for (uint k = 56u; k < 64u; ++k) results[o + k] = 0u;
}
