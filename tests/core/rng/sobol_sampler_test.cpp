#include "core/rng/sobol_sampler.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace sst {
namespace {

// For a (0,2)-sequence in base 2, the first 2^k points put exactly one point in every
// elementary interval of area 2^-k (2^a columns x 2^(k-a) rows); Owen scrambling keeps that.
TEST(SobolSampler, EveryPowerOfTwoPrefixIsStratified) {
  const int k = 8, n = 1 << k;
  for (uint32_t pixel : {0u, 17u, 123456u})
    for (int set = 0; set < 3; ++set) {
      std::vector<vec2> points;
      for (int i = 0; i < n; ++i) {
        PixelSampler s = pixel_sampler(42, pixel, uint32_t(i));
        for (int skip = 0; skip < set; ++skip) pixel_sampler_get2d(s);
        points.push_back(pixel_sampler_get2d(s));
      }
      for (int a = 0; a <= k; ++a) {
        int columns = 1 << a, rows = 1 << (k - a);
        std::set<int> cells;
        for (vec2 p : points) cells.insert(int(p.x * columns) * rows + int(p.y * rows));
        EXPECT_EQ(int(cells.size()), n) << "pixel " << pixel << " set " << set << " grid " << columns << "x" << rows;
      }
    }
}

TEST(SobolSampler, PixelsAndSetsAreDecorrelated) {
  std::set<uint32_t> first_points;
  for (uint32_t pixel = 0; pixel < 1024; ++pixel) {
    PixelSampler first = pixel_sampler(1, pixel, 0);
    first_points.insert(uint32_t(pixel_sampler_get2d(first).x * 1e6f));
  }
  EXPECT_GT(first_points.size(), 1000u);
  PixelSampler s = pixel_sampler(1, 5, 0);
  vec2 a = pixel_sampler_get2d(s), b = pixel_sampler_get2d(s);
  EXPECT_NE(a, b);
  EXPECT_EQ(s.sets_used, 2u);
}

TEST(SobolSampler, MeanOverManyPixelsIsUniform) {
  double sum = 0.0;
  const int pixels = 4096;
  for (int p = 0; p < pixels; ++p) {
    PixelSampler s = pixel_sampler(3, uint32_t(p), 7);
    pixel_sampler_get2d(s);
    sum += pixel_sampler_get2d(s).y;
  }
  EXPECT_NEAR(sum / pixels, 0.5, 6.0 * std::sqrt(1.0 / 12.0 / pixels));
}

// The textbook generator: direction v_k = v_(k-1) ^ (v_(k-1) >> 1), v_0 = 2^31, xored in for each
// set index bit k.
uint sobol_dimension1_by_directions(uint index) {
  uint result = 0u;
  for (uint v = 1u << 31u; index != 0u; index >>= 1u, v ^= v >> 1u)
    if ((index & 1u) != 0u) result ^= v;
  return result;
}

TEST(SobolSampler, SecondDimensionEqualsTheDirectionNumbers) {
  std::mt19937 rng(5);
  uint64_t differing = 0;
  for (uint i = 0; i < (1u << 16); ++i) {
    uint r = uint(rng());
    differing += sobol_dimension1(i) != sobol_dimension1_by_directions(i);
    differing += sobol_dimension1(r) != sobol_dimension1_by_directions(r);
  }
  for (uint k = 0; k < 32; ++k) differing += sobol_dimension1(1u << k) != sobol_dimension1_by_directions(1u << k);
  differing += sobol_dimension1(~0u) != sobol_dimension1_by_directions(~0u);
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(sobol_dimension1_reversed(12345u), bitfieldReverse(sobol_dimension1_by_directions(12345u)));
}

TEST(SobolSampler, RemapKeepsTheUnitInterval) {
  EXPECT_FLOAT_EQ(remap_below(0.25f, 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(remap_above(0.75f, 0.5f), 0.5f);
  EXPECT_LT(remap_below(0.49999997f, 0.5f), 1.0f);
}

}  // namespace
}  // namespace sst
