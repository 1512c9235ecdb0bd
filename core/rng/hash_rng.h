// Counter-based random numbers: every value is a pure function of (seed, pixel, sample index,
// dimension), so images are the same bits whatever the thread count or tile order, and the GLSL
// port (gpu/shaders/hash_rng.glsl, same constants) draws the same numbers on the GPU.
// The mixing function is the PCG hash of Jarzynski & Olano, "Hash Functions for GPU Rendering"
// (JCGT 2020), which passes BigCrush as a hash of a counter.
#pragma once
#include <cstdint>

namespace sst {

inline uint32_t pcg_hash(uint32_t v) {
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Maps 32 random bits to [0, 1): 24 bits so that the result is exactly representable and < 1.
inline float bits_to_unit_float(uint32_t bits) { return float(bits >> 8) * (1.0f / 16777216.0f); }

// The random stream of one pixel sample. Dimensions are consumed in a fixed order by each
// integrator; `stream` separates independent uses (e.g. VPL generation vs. pixel sampling).
class HashRng {
 public:
  HashRng(uint32_t seed, uint32_t pixel, uint32_t sample, uint32_t stream = 0)
      : key_(pcg_hash(seed ^ pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(stream))))) {}
  uint32_t next_bits() { return pcg_hash(key_ + 0x9E3779B9u * ++dimension_); }
  float next() { return bits_to_unit_float(next_bits()); }

 private:
  uint32_t key_;
  uint32_t dimension_ = 0;
};

}  // namespace sst
