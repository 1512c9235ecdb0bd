// GLSL port of core/rng/sobol_sampler.h (Burley 2020 hash-based Owen-scrambled Sobol; same
// constants and order), so pixel samples are the same bits on the GPU as on the CPU.
#ifndef SST_SOBOL_SAMPLER_GLSL
#define SST_SOBOL_SAMPLER_GLSL
#include "gpu/shaders/hash_rng.glsl"

uint reverse_bits(uint x) { return bitfieldReverse(x); }

uint laine_karras_permutation(uint x, uint seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

uint nested_uniform_scramble(uint x, uint seed) { return reverse_bits(laine_karras_permutation(reverse_bits(x), seed)); }

uint sobol_dimension1(uint index) {
  uint result = 0u;
  for (uint v = 1u << 31; index != 0u; index >>= 1, v ^= v >> 1)
    if ((index & 1u) != 0u) result ^= v;
  return result;
}

struct PixelSampler {
  uint key;
  uint reversed_index;
  uint set_index;
};

PixelSampler pixel_sampler(uint seed, uint pixel, uint sample_index) {
  return PixelSampler(pcg_hash(seed ^ pcg_hash(pixel ^ 0x2545F491u)), reverse_bits(sample_index), 0u);
}

vec2 pixel_sampler_get2d(inout PixelSampler s) {
  uint set_seed = pcg_hash(s.key ^ pcg_hash(++s.set_index));
  uint i = reverse_bits(laine_karras_permutation(s.reversed_index, set_seed));
  uint x = reverse_bits(laine_karras_permutation(i, pcg_hash(set_seed ^ 0xA511E9B3u)));
  uint y = nested_uniform_scramble(sobol_dimension1(i), pcg_hash(set_seed ^ 0x63D83595u));
  return vec2(bits_to_unit_float(x), bits_to_unit_float(y));
}

float pixel_sampler_get1d(inout PixelSampler s) { return pixel_sampler_get2d(s).x; }

#endif
