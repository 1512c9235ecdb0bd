#include "core/math/radix_sort.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "core/util/error.h"

namespace sst {
namespace {

struct Pairs {
  std::vector<uint64_t> keys;
  std::vector<uint32_t> values;
};

// Random keys spread over all 64 bits, drawn from `distinct` values (many duplicates when
// distinct is small; 0: every key drawn afresh); values = input position, which exposes any
// instability.
Pairs random_pairs(size_t n, size_t distinct, uint32_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<uint64_t> pool(distinct);
  for (uint64_t& k : pool) k = rng();
  Pairs p;
  for (size_t i = 0; i < n; ++i) {
    p.keys.push_back(distinct == 0 ? rng() : pool[rng() % distinct]);
    p.values.push_back(uint32_t(i));
  }
  return p;
}

// The reference: std::stable_sort of the pairs by key.
Pairs reference_sort(const Pairs& in) {
  std::vector<uint32_t> order(in.keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return in.keys[a] < in.keys[b]; });
  Pairs out;
  for (uint32_t i : order) {
    out.keys.push_back(in.keys[i]);
    out.values.push_back(in.values[i]);
  }
  return out;
}

class RadixSortSizes : public ::testing::TestWithParam<size_t> {};

TEST_P(RadixSortSizes, MatchesStableStdSortWithAndWithoutDuplicates) {
  size_t n = GetParam();
  for (size_t distinct : {1, 7, 0}) {
    Pairs in = random_pairs(n, distinct, uint32_t(n + distinct));
    Pairs expected = reference_sort(in);
    Pairs got = in;
    radix_sort_pairs(got.keys, got.values);
    EXPECT_EQ(got.keys, expected.keys) << "n " << n << " distinct " << distinct;
    EXPECT_EQ(got.values, expected.values) << "n " << n << " distinct " << distinct;
  }
}

INSTANTIATE_TEST_SUITE_P(RadixSort, RadixSortSizes,
                         ::testing::Values(size_t(0), size_t(1), size_t(2), size_t(3), size_t(1000),
                                           (size_t(1) << 16) + 1));

TEST(RadixSort, SortsKeysWithFewDifferingBitsAndScratchReuse) {
  // Keys that differ only in bits 20..23 and 60..63: the other passes are skipped.
  std::mt19937_64 rng(2);
  Pairs in;
  for (uint32_t i = 0; i < 50000; ++i) {
    in.keys.push_back(((rng() & 15u) << 20) | ((rng() & 15u) << 60));
    in.values.push_back(i);
  }
  Pairs expected = reference_sort(in);
  RadixSortScratch scratch;
  for (int round = 0; round < 2; ++round) {
    Pairs got = in;
    radix_sort_pairs(got.keys, got.values, scratch);
    EXPECT_EQ(got.keys, expected.keys);
    EXPECT_EQ(got.values, expected.values);
  }
}

TEST(RadixSort, BitRangeSkipsLowBitsThatAreAlreadyAscending) {
  // What the light tree does: low 25 bits = input index, sort bits [25, 64) only.
  std::mt19937_64 rng(3);
  Pairs in;
  for (uint32_t i = 0; i < 70000; ++i) {
    in.keys.push_back(((rng() % 1000u) << 25) | i);
    in.values.push_back(i);
  }
  Pairs expected = reference_sort(in);
  Pairs got = in;
  radix_sort_pairs(got.keys, got.values, 25, 64);
  EXPECT_EQ(got.keys, expected.keys);
  EXPECT_EQ(got.values, expected.values);
  // The keys alone come out the same: their low bits are the payload.
  std::vector<uint64_t> keys_only = in.keys;
  RadixSortScratch scratch;
  radix_sort_keys(keys_only, scratch, 25, 64);
  EXPECT_EQ(keys_only, expected.keys);
  EXPECT_THROW(radix_sort_keys(keys_only, scratch, 0, 65), Error);
}

TEST(RadixSort, SameResultWithOneAndTwoThreads) {
  Pairs in = random_pairs(200000, 1000, 4);
  Pairs one = in, two = in;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    radix_sort_pairs(one.keys, one.values);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    radix_sort_pairs(two.keys, two.values);
  }
  EXPECT_EQ(one.keys, two.keys);
  EXPECT_EQ(one.values, two.values);
}

TEST(RadixSort, RejectsMismatchedArraysAndBadBitRanges) {
  std::vector<uint64_t> keys(3);
  std::vector<uint32_t> values(2);
  EXPECT_THROW(radix_sort_pairs(keys, values), Error);
  values.resize(3);
  EXPECT_THROW(radix_sort_pairs(keys, values, -1, 64), Error);
  EXPECT_THROW(radix_sort_pairs(keys, values, 0, 65), Error);
  EXPECT_THROW(radix_sort_pairs(keys, values, 40, 30), Error);
  EXPECT_NO_THROW(radix_sort_pairs(keys, values, 30, 30));
}

}  // namespace
}  // namespace sst
