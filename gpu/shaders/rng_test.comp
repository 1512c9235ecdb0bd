#version 450
#extension GL_GOOGLE_include_directive : require
// Writes the RNGs' outputs for indices 0..count-1 so a test can compare them with the C++ bits.
#include "core/rng/sobol_sampler.h"

layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer Out { uint values[]; };
layout(push_constant) uniform Push { uint seed; uint count; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) return;
  HashRng rng = hash_rng(seed, i, 7u, 3u);
  PixelSampler ps = pixel_sampler(seed, i, i * 3u);
  vec2 a = pixel_sampler_get2d(ps);
  vec2 b = pixel_sampler_get2d(ps);
  uint o = i * 8u;
  values[o + 0u] = pcg_hash(i);
  values[o + 1u] = hash_rng_next_bits(rng);
  values[o + 2u] = floatBitsToUint(hash_rng_next(rng));
  values[o + 3u] = floatBitsToUint(a.x);
  values[o + 4u] = floatBitsToUint(a.y);
  values[o + 5u] = floatBitsToUint(b.x);
  values[o + 6u] = floatBitsToUint(b.y);
  values[o + 7u] = sobol_dimension1(i);
}
