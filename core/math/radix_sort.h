// Parallel LSD radix sort of (64-bit key, 32-bit value) pairs with oneTBB: 8-bit digits, one
// histogram per block of the input, an exclusive prefix sum over (digit, block), then a scatter
// in which every block writes its elements in input order. Each pass is therefore stable, and a
// stable sort has exactly one result, so the output does not depend on the thread count.
#pragma once
#include <cstdint>
#include <vector>

namespace sst {

// Buffers a sort needs besides its input; keep one around to sort again without allocating.
struct RadixSortScratch {
  std::vector<uint64_t> keys;
  std::vector<uint32_t> values;
  std::vector<uint32_t> counts;  // per-block digit histograms, then their scatter offsets
};

// Sorts `keys` ascending and permutes `values` alongside, stably. Only the key bits
// [begin_bit, end_bit) take part: callers whose low bits already come in ascending order in the
// input (the VPL id of a sort key, see sort_key.h) skip them, and the result equals a full sort.
// Passes in which every key has the same digit are skipped. Throws sst::Error if the arrays
// differ in size or the bit range is not within [0, 64].
void radix_sort_pairs(std::vector<uint64_t>& keys, std::vector<uint32_t>& values, RadixSortScratch& scratch,
                      int begin_bit = 0, int end_bit = 64);
void radix_sort_pairs(std::vector<uint64_t>& keys, std::vector<uint32_t>& values, int begin_bit = 0,
                      int end_bit = 64);
// The keys alone, for keys that carry their own payload (a sort key's VPL id): a third less
// memory traffic per pass than radix_sort_pairs.
void radix_sort_keys(std::vector<uint64_t>& keys, RadixSortScratch& scratch, int begin_bit = 0, int end_bit = 64);

}  // namespace sst
