// GLSL port of core/rng/hash_rng.h (same constants, same order): the GPU draws the same numbers
// as the CPU for the same (seed, pixel, sample, stream, dimension).
#ifndef SST_HASH_RNG_GLSL
#define SST_HASH_RNG_GLSL

uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float bits_to_unit_float(uint bits) { return float(bits >> 8) * (1.0 / 16777216.0); }

struct HashRng {
  uint key;
  uint dimension;
};

HashRng hash_rng(uint seed, uint pixel, uint sample_index, uint stream) {
  return HashRng(pcg_hash(seed ^ pcg_hash(pixel ^ pcg_hash(sample_index ^ pcg_hash(stream)))), 0u);
}

uint hash_rng_next_bits(inout HashRng rng) { return pcg_hash(rng.key + 0x9E3779B9u * ++rng.dimension); }
float hash_rng_next(inout HashRng rng) { return bits_to_unit_float(hash_rng_next_bits(rng)); }

#endif
