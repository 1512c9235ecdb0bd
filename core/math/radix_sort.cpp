#include "core/math/radix_sort.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>

#include "core/math/radix_digit.h"
#include "core/util/error.h"

namespace sst {
namespace {

constexpr int kDigitBits = 8;
constexpr uint32_t kBuckets = 1u << kDigitBits;
// Blocks small enough to share the work between threads, big enough that the per-block
// histograms (kBuckets counters each) stay small next to the data.
constexpr size_t kMinBlock = 16384;
constexpr size_t kMaxBlocks = 64;

struct Blocks {
  size_t size = 0, count = 0;
  size_t begin(size_t b) const { return b * size; }
  size_t end(size_t b, size_t n) const { return std::min(n, (b + 1) * size); }
};

Blocks split(size_t n) {
  Blocks blocks;
  blocks.size = std::max(kMinBlock, (n + kMaxBlocks - 1) / kMaxBlocks);
  blocks.count = (n + blocks.size - 1) / blocks.size;
  return blocks;
}

void histogram(const uint64_t* keys, size_t n, const Blocks& blocks, int shift, uint32_t mask,
               uint32_t* counts) {
  tbb::parallel_for(size_t(0), blocks.count, [&](size_t b) {
    uint32_t* c = counts + b * kBuckets;
    std::fill(c, c + kBuckets, 0u);
    for (size_t i = blocks.begin(b), e = blocks.end(b, n); i < e; ++i) ++c[radix_digit(keys[i], uint32_t(shift), mask)];
  });
}

// Turns the counts into each (block, digit)'s first output slot: digits in order, and within a
// digit, blocks in input order (which keeps the pass stable). Returns false when one digit holds
// every key, so the pass would not move anything.
bool exclusive_offsets(uint32_t* counts, size_t n, size_t block_count) {
  uint32_t running = 0;
  for (uint32_t d = 0; d < kBuckets; ++d) {
    uint32_t digit_total = 0;
    for (size_t b = 0; b < block_count; ++b) {
      uint32_t c = counts[b * kBuckets + d];
      counts[b * kBuckets + d] = running + digit_total;
      digit_total += c;
    }
    if (digit_total == n) return false;
    running += digit_total;
  }
  return true;
}

// kWithValues = false: `values` and `values_out` are not touched (may be null).
template <bool kWithValues>
void scatter(const uint64_t* keys, const uint32_t* values, size_t n, const Blocks& blocks, int shift,
             uint32_t mask, uint32_t* offsets, uint64_t* keys_out, uint32_t* values_out) {
  tbb::parallel_for(size_t(0), blocks.count, [&](size_t b) {
    uint32_t* offset = offsets + b * kBuckets;
    for (size_t i = blocks.begin(b), e = blocks.end(b, n); i < e; ++i) {
      uint32_t slot = offset[radix_digit(keys[i], uint32_t(shift), mask)]++;
      keys_out[slot] = keys[i];
      if constexpr (kWithValues) values_out[slot] = values[i];
    }
  });
}

void check_bit_range(int begin_bit, int end_bit) {
  if (begin_bit < 0 || end_bit > 64 || begin_bit > end_bit)
    throw Error("radix_sort: bit range [" + std::to_string(begin_bit) + ", " + std::to_string(end_bit) +
                ") is not within [0, 64]");
}

// The passes of both entry points; values == nullptr sorts the keys alone.
void sort_passes(std::vector<uint64_t>& keys, std::vector<uint32_t>* values, RadixSortScratch& scratch, int begin_bit,
                 int end_bit) {
  if (keys.size() > UINT32_MAX) throw Error("radix_sort: more than 2^32-1 keys");
  const size_t n = keys.size();
  if (n < 2) return;
  Blocks blocks = split(n);
  scratch.keys.resize(n);
  if (values) scratch.values.resize(n);
  scratch.counts.resize(blocks.count * kBuckets);
  for (int shift = begin_bit; shift < end_bit; shift += kDigitBits) {
    int bits = std::min(kDigitBits, end_bit - shift);
    uint32_t mask = (1u << bits) - 1u;
    histogram(keys.data(), n, blocks, shift, mask, scratch.counts.data());
    if (!exclusive_offsets(scratch.counts.data(), n, blocks.count)) continue;
    if (values)
      scatter<true>(keys.data(), values->data(), n, blocks, shift, mask, scratch.counts.data(), scratch.keys.data(),
                    scratch.values.data());
    else
      scatter<false>(keys.data(), nullptr, n, blocks, shift, mask, scratch.counts.data(), scratch.keys.data(), nullptr);
    // The sorted pass now lives in the scratch buffers: swap (O(1)) so `keys` holds it.
    keys.swap(scratch.keys);
    if (values) values->swap(scratch.values);
  }
}

}  // namespace

void radix_sort_pairs(std::vector<uint64_t>& keys, std::vector<uint32_t>& values, RadixSortScratch& scratch,
                      int begin_bit, int end_bit) {
  if (keys.size() != values.size())
    throw Error("radix_sort_pairs: keys (" + std::to_string(keys.size()) + ") and values (" +
                std::to_string(values.size()) + ") differ in size");
  check_bit_range(begin_bit, end_bit);
  sort_passes(keys, &values, scratch, begin_bit, end_bit);
}

void radix_sort_keys(std::vector<uint64_t>& keys, RadixSortScratch& scratch, int begin_bit, int end_bit) {
  check_bit_range(begin_bit, end_bit);
  sort_passes(keys, nullptr, scratch, begin_bit, end_bit);
}

void radix_sort_pairs(std::vector<uint64_t>& keys, std::vector<uint32_t>& values, int begin_bit, int end_bit) {
  RadixSortScratch scratch;
  radix_sort_pairs(keys, values, scratch, begin_bit, end_bit);
}

}  // namespace sst
