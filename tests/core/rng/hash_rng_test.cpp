#include "core/rng/hash_rng.h"

#include <gtest/gtest.h>

#include <set>

namespace sst {
namespace {

TEST(HashRng, KnownValuesPinTheSequence) {
  // The GLSL port must reproduce these; a change here changes every image.
  EXPECT_EQ(pcg_hash(0u), 129708002u);
  EXPECT_EQ(pcg_hash(1u), 2831084092u);
  HashRng a = hash_rng(1, 2, 3), b = hash_rng(1, 2, 3);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(hash_rng_next_bits(a), hash_rng_next_bits(b));
}

TEST(HashRng, StreamsDiffer) {
  std::set<uint32_t> first;
  for (uint32_t seed = 0; seed < 4; ++seed)
    for (uint32_t pixel = 0; pixel < 64; ++pixel)
      for (uint32_t sample = 0; sample < 16; ++sample) {
        HashRng rng = hash_rng(seed, pixel, sample);
        first.insert(hash_rng_next_bits(rng));
      }
  EXPECT_GT(first.size(), 4096u - 3u);  // collisions of 32-bit values are rare
}

TEST(HashRng, UniformMoments) {
  HashRng rng = hash_rng(42, 7, 0);
  double sum = 0.0, sum2 = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    float u = hash_rng_next(rng);
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    sum += u;
    sum2 += double(u) * u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n, 1.0 / 3.0, 0.005);
}

}  // namespace
}  // namespace sst
