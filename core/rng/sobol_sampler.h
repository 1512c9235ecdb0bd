// Stratified pixel samples: Owen-scrambled Sobol points with hash-based scrambling (Burley,
// "Practical Hash-based Owen Scrambling", JCGT 2020). Each request draws a fresh 2D point set
// (Sobol dimensions 0 and 1, a (0,2)-sequence) whose index order and digits are scrambled by
// hashes of (seed, pixel, set): every prefix of 2^k samples is stratified, pixels and sets are
// decorrelated, and the value is a pure function of its counters, like HashRng (same bits on
// any thread count and on both backends: shared C++/GLSL source).
//
// Compared with independent random numbers this lowers the error of the many low-dimensional
// integrals a renderer does (pixel area, light position, BRDF direction) at the same sample
// count; Cycles' references use a stratified pattern too (progressive multi-jitter).
#ifndef SST_CORE_RNG_SOBOL_SAMPLER_H
#define SST_CORE_RNG_SOBOL_SAMPLER_H
#include "core/math/vector_math.h"
#include "core/rng/hash_rng.h"

SST_BEGIN

// Laine-Karras style hash whose output bits depend only on the input bits below them, which
// is what an Owen scramble of a bit-reversed value needs (Burley's improved constants).
SST_FUNC uint laine_karras_permutation(uint x, uint seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16u) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

// The second Sobol dimension as a 32-bit fraction (the first is bitfieldReverse(index)),
// bit-reversed. Its generator matrix is Pascal's triangle mod 2: index bit k contributes
// (1 + S)^k e_31, S a right shift; in reversed bit order that is the polynomial in S whose
// coefficient of S^j sits at bit j, and the index itself is sum_k index_k S^k. So the map is the
// substitution S -> 1 + S, and as (1 + S)^(2^m) = 1 + S^(2^m) mod 2, it is one masked shift-xor per
// bit m of the exponents: every S^j with bit m set gains S^(j - 2^m). Equal to the bitwise loop
// over the index (tests/core/rng), without its 32 data-dependent branches.
SST_FUNC uint sobol_dimension1_reversed(uint index) {
  uint x = index;
  x ^= (x & 0xFFFF0000u) >> 16u;
  x ^= (x & 0xFF00FF00u) >> 8u;
  x ^= (x & 0xF0F0F0F0u) >> 4u;
  x ^= (x & 0xCCCCCCCCu) >> 2u;
  x ^= (x & 0xAAAAAAAAu) >> 1u;
  return x;
}

SST_FUNC uint sobol_dimension1(uint index) { return bitfieldReverse(sobol_dimension1_reversed(index)); }

struct PixelSampler {
  uint key;
  uint reversed_index;
  uint sets_used;  // 2D point sets drawn so far
};

SST_FUNC PixelSampler pixel_sampler(uint seed, uint pixel, uint sample_index) {
  PixelSampler s;
  s.key = pcg_hash(seed ^ pcg_hash(pixel ^ 0x2545F491u));
  s.reversed_index = bitfieldReverse(sample_index);
  s.sets_used = 0u;
  return s;
}

// The nested uniform scramble of the Sobol values of the scrambled index, a value v scrambled as
// bitfieldReverse(laine_karras_permutation(bitfieldReverse(v), seed)); both dimensions are at hand
// bit-reversed (dimension 0 is the index reversed), so the inner bitfieldReverse cancels and is
// not written. This runs a dozen times per path.
SST_FUNC vec2 pixel_sampler_get2d(SST_INOUT(PixelSampler) s) {
  s.sets_used += 1u;
  uint set_seed = pcg_hash(s.key ^ pcg_hash(s.sets_used));
  uint i = bitfieldReverse(laine_karras_permutation(s.reversed_index, set_seed));
  uint x = bitfieldReverse(laine_karras_permutation(i, pcg_hash(set_seed ^ 0xA511E9B3u)));
  uint y = bitfieldReverse(laine_karras_permutation(sobol_dimension1_reversed(i), pcg_hash(set_seed ^ 0x63D83595u)));
  return vec2(bits_to_unit_float(x), bits_to_unit_float(y));
}

// The compilers drop get2d's unused y. (A get1d written out separately measured the same on slc's
// and sst's walks but made rtslc's sampling 8% slower through GCC's inlining choices.)
SST_FUNC float pixel_sampler_get1d(SST_INOUT(PixelSampler) s) { return pixel_sampler_get2d(s).x; }

// Reuses the part of u below/above a threshold p as a fresh uniform number, so one 2D sample
// can both choose (with probability p) and then place a point without losing stratification.
SST_FUNC float remap_below(float u, float p) { return min(u / p, kOneMinusEpsilon); }
SST_FUNC float remap_above(float u, float p) {
  SST_PRECISE float r = (u - p) / (1.0f - p);
  return min(r, kOneMinusEpsilon);
}

SST_END

#endif  // SST_CORE_RNG_SOBOL_SAMPLER_H
