// The digit of a 64-bit key that one pass of an LSD radix sort orders by, for both backends'
// sorts of the light-tree build (shared C++/GLSL source, core/math/cpu_gpu.h). The passes
// themselves (histograms, scan, scatter) are per backend: radix_sort.cpp, light_tree_sort_*.comp.
#ifndef SST_CORE_MATH_RADIX_DIGIT_H
#define SST_CORE_MATH_RADIX_DIGIT_H
#include "core/math/cpu_gpu.h"

SST_BEGIN

// Bits [shift, shift + bits) of a key held as (low, high) words, where mask = 2^bits - 1 and
// shift < 64.
SST_FUNC uint radix_digit(uvec2 key, uint shift, uint mask) {
  uint word;
  if (shift >= 32u)
    word = key.y >> (shift - 32u);
  else if (shift == 0u)
    word = key.x;
  else
    word = (key.x >> shift) | (key.y << (32u - shift));
  return word & mask;
}

SST_END

#ifdef __cplusplus
namespace sst {
inline uint radix_digit(uint64_t key, uint shift, uint mask) {
  return radix_digit(uvec2(uint32_t(key), uint32_t(key >> 32)), shift, mask);
}
}  // namespace sst
#endif

#endif  // SST_CORE_MATH_RADIX_DIGIT_H
