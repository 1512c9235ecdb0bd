// Counter-based random numbers: every value is a pure function of (seed, pixel, sample index,
// stream, dimension), so images are the same bits whatever the thread count or tile order, and
// both backends draw the same numbers (shared C++/GLSL source, core/math/cpu_gpu.h).
// The mixing function is the PCG hash of Jarzynski & Olano, "Hash Functions for GPU Rendering"
// (JCGT 2020), which passes BigCrush as a hash of a counter.
#ifndef SST_CORE_RNG_HASH_RNG_H
#define SST_CORE_RNG_HASH_RNG_H
#include "core/math/cpu_gpu.h"

SST_BEGIN

SST_FUNC uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Maps 32 random bits to [0, 1): 24 bits so that the result is exactly representable and < 1.
SST_FUNC float bits_to_unit_float(uint bits) { return float(bits >> 8u) * (1.0f / 16777216.0f); }

// The random stream of one pixel sample. Dimensions are consumed in a fixed order by each
// integrator; `stream` separates independent uses (e.g. VPL generation vs. pixel sampling).
struct HashRng {
  uint key;
  uint dimension;
};

SST_FUNC HashRng hash_rng(uint seed, uint pixel, uint sample_index, uint stream) {
  HashRng rng;
  rng.key = pcg_hash(seed ^ pcg_hash(pixel ^ pcg_hash(sample_index ^ pcg_hash(stream))));
  rng.dimension = 0u;
  return rng;
}

SST_FUNC uint hash_rng_next_bits(SST_INOUT(HashRng) rng) {
  rng.dimension += 1u;
  return pcg_hash(rng.key + 0x9E3779B9u * rng.dimension);
}

SST_FUNC float hash_rng_next(SST_INOUT(HashRng) rng) { return bits_to_unit_float(hash_rng_next_bits(rng)); }

SST_END

#ifdef __cplusplus
namespace sst {
// Stream 0, the pixel samples' own.
inline HashRng hash_rng(uint seed, uint pixel, uint sample_index) { return hash_rng(seed, pixel, sample_index, 0u); }
}  // namespace sst
#endif

#endif  // SST_CORE_RNG_HASH_RNG_H
