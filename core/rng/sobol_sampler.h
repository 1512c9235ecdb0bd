// Stratified pixel samples: Owen-scrambled Sobol points with hash-based scrambling (Burley,
// "Practical Hash-based Owen Scrambling", JCGT 2020). Each request draws a fresh 2D point set
// (Sobol dimensions 0 and 1, a (0,2)-sequence) whose index order and digits are scrambled by
// hashes of (seed, pixel, set): every prefix of 2^k samples is stratified, pixels and sets are
// decorrelated, and the value is a pure function of its counters, like HashRng (same bits on
// any thread count; the GLSL port uses the same constants).
//
// Compared with independent random numbers this lowers the error of the many low-dimensional
// integrals a renderer does (pixel area, light position, BRDF direction) at the same sample
// count; Cycles' references use a stratified pattern too (progressive multi-jitter).
#pragma once
#include <cstdint>

#include "core/math/math.h"
#include "core/rng/hash_rng.h"

namespace sst {

inline uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// Laine-Karras style hash whose output bits depend only on the input bits below them, which
// is what an Owen scramble of a bit-reversed value needs (Burley's improved constants).
inline uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

inline uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
  return reverse_bits(laine_karras_permutation(reverse_bits(x), seed));
}

// The first two Sobol dimensions as 32-bit fractions.
inline uint32_t sobol_dimension0(uint32_t index) { return reverse_bits(index); }
inline uint32_t sobol_dimension1(uint32_t index) {
  uint32_t result = 0;
  for (uint32_t v = 1u << 31; index; index >>= 1, v ^= v >> 1)
    if (index & 1u) result ^= v;
  return result;
}

class PixelSampler {
 public:
  PixelSampler(uint32_t seed, uint32_t pixel, uint32_t sample_index)
      : key_(pcg_hash(seed ^ pcg_hash(pixel ^ 0x2545F491u))), reversed_index_(reverse_bits(sample_index)) {}

  // Equal to nested_uniform_scramble of the Sobol values of the scrambled index; written with
  // reverse_bits(reverse_bits(x)) = x folded away, since this runs a dozen times per path.
  vec2 get2d() {
    uint32_t set_seed = pcg_hash(key_ ^ pcg_hash(++set_));
    uint32_t i = reverse_bits(laine_karras_permutation(reversed_index_, set_seed));
    uint32_t x = reverse_bits(laine_karras_permutation(i, pcg_hash(set_seed ^ 0xA511E9B3u)));
    uint32_t y = nested_uniform_scramble(sobol_dimension1(i), pcg_hash(set_seed ^ 0x63D83595u));
    return {bits_to_unit_float(x), bits_to_unit_float(y)};
  }
  float get1d() { return get2d().x; }
  uint32_t sets_used() const { return set_; }

 private:
  uint32_t key_;
  uint32_t reversed_index_;
  uint32_t set_ = 0;
};

// Reuses the part of u below/above a threshold p as a fresh uniform number, so one 2D sample
// can both choose (with probability p) and then place a point without losing stratification.
inline float remap_below(float u, float p) { return std::min(u / p, 0.99999994f); }
inline float remap_above(float u, float p) { return std::min((u - p) / (1.0f - p), 0.99999994f); }

}  // namespace sst
