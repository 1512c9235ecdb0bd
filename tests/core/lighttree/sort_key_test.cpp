#include "core/lighttree/sort_key.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "core/util/error.h"
#include "tests/core/lighttree/lighttree_test_util.h"

namespace sst {
namespace {

// Bit-by-bit interleave, the definition the magic-number version must match.
uint32_t reference_morton(uint32_t x, uint32_t y, uint32_t z) {
  uint32_t code = 0;
  for (int bit = 9; bit >= 0; --bit)
    code = (code << 3) | (((x >> bit) & 1u) << 2) | (((y >> bit) & 1u) << 1) | ((z >> bit) & 1u);
  return code;
}

// The paper's recursive definition (Fig. 3), in float: at each level pick the corner triangle
// whose coordinate is >= 1/2, else the middle one, and map to its own coordinates.
uint32_t reference_normal_code(vec3 n) {
  uint32_t code = (n.x < 0.0f ? 4u : 0u) | (n.y < 0.0f ? 2u : 0u) | (n.z < 0.0f ? 1u : 0u);
  vec3 m = glm::abs(n);
  float sum = m.x + m.y + m.z;
  float a = m.x / sum, b = m.y / sum, c = m.z / sum;
  for (int level = 0; level < 3; ++level) {
    uint32_t sub;
    if (a >= 0.5f) {
      sub = 0, a = 2 * a - 1, b = 2 * b, c = 2 * c;
    } else if (b >= 0.5f) {
      sub = 1, a = 2 * a, b = 2 * b - 1, c = 2 * c;
    } else if (c >= 0.5f) {
      sub = 2, a = 2 * a, b = 2 * b, c = 2 * c - 1;
    } else {
      sub = 3, a = 1 - 2 * a, b = 1 - 2 * b, c = 1 - 2 * c;
    }
    code = (code << 2) | sub;
  }
  return code;
}

float angle(vec3 a, vec3 b) { return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f)); }

TEST(SortKey, MortonMatchesBitByBitInterleave) {
  std::mt19937 rng(1);
  for (int i = 0; i < 10000; ++i) {
    uint32_t x = rng() & 1023u, y = rng() & 1023u, z = rng() & 1023u;
    ASSERT_EQ(morton_code(x, y, z), reference_morton(x, y, z));
  }
  EXPECT_EQ(morton_code(1, 0, 0), 4u);
  EXPECT_EQ(morton_code(0, 1, 0), 2u);
  EXPECT_EQ(morton_code(0, 0, 1), 1u);
  EXPECT_EQ(morton_code(1023, 1023, 1023), (1u << 30) - 1u);
}

TEST(SortKey, GridNormalisesToTheBoxAndMapsDegenerateAxesToZero) {
  Bounds3 box{vec3(-2.0f, 5.0f, 1.0f), vec3(2.0f, 5.0f, 3.0f)};  // no extent along y
  MortonGrid grid = MortonGrid::over(box);
  EXPECT_EQ(grid.scale.y, 0.0f);
  EXPECT_EQ(grid.code(box.lo), 0u);
  EXPECT_EQ(grid.code(box.hi), morton_code(1023, 0, 1023));
  EXPECT_EQ(grid.code(box.center()), morton_code(512, 0, 512));
  // Outside the box (cannot happen for the VPLs it was made from) clamps instead of wrapping.
  EXPECT_EQ(grid.code(vec3(-100.0f, 7.0f, 100.0f)), morton_code(0, 0, 1023));
  // All VPLs at one point: every axis degenerate.
  Bounds3 point{vec3(1.0f), vec3(1.0f)};
  EXPECT_EQ(MortonGrid::over(point).code(vec3(1.0f)), 0u);
}

TEST(SortKey, KeyLayoutPutsPositionAboveNormalAboveId) {
  uint64_t key = make_sort_key((1u << 30) - 1u, 511u, uint32_t(kMaxSortKeyVpls - 1));
  EXPECT_EQ(key, ~uint64_t(0));
  EXPECT_EQ(make_sort_key(1, 0, 0) >> 34, 1u);
  EXPECT_EQ((make_sort_key(0, 1, 0) >> 25) & 511u, 1u);
  EXPECT_EQ(kIdBits, 25);
  EXPECT_EQ(kMaxSortKeyVpls, 33554432u);
  // Position dominates the normal, which dominates the id.
  EXPECT_LT(make_sort_key(0, 511, 7), make_sort_key(1, 0, 0));
  EXPECT_LT(make_sort_key(3, 0, uint32_t(kMaxSortKeyVpls - 1)), make_sort_key(3, 1, 0));
}

TEST(SortKey, ComputeKeysCarriesIdsAndRejectsTooManyVpls) {
  VplSet vpls = test::random_vpls(100, 3);
  std::vector<uint64_t> keys;
  compute_sort_keys(vpls, compute_vpl_bounds(vpls), keys);
  ASSERT_EQ(keys.size(), 100u);
  for (uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(sort_key_vpl(keys[i]), i);
    EXPECT_EQ(keys[i] & (kMaxSortKeyVpls - 1), i);
    EXPECT_EQ((keys[i] >> 25) & 511u, quantize_normal(vpls[i].normal));
  }
}

TEST(SortKey, CapacityIsTwoToThe25Vpls) {
  EXPECT_NO_THROW(check_sort_key_capacity(kMaxSortKeyVpls));
  try {
    check_sort_key_capacity(kMaxSortKeyVpls + 1);
    FAIL() << "expected sst::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "light tree: 33554433 VPLs exceed the sort key's limit of 33554432 (25 id bits)");
  }
}

TEST(SortKey, VplBoundsRejectBadVplsByIndex) {
  VplSet vpls = test::random_vpls(10, 4);
  vpls[7].intensity.y = -1.0f;
  vpls[8].position.x = std::nanf("");
  try {
    compute_vpl_bounds(vpls);
    FAIL() << "expected sst::Error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "light tree: vpl 7: intensity is negative or not finite");
  }
  vpls = test::random_vpls(10, 4);
  vpls[2].normal = vec3(0.0f);
  EXPECT_THROW(compute_vpl_bounds(vpls), Error);
  EXPECT_TRUE(compute_vpl_bounds({}).empty());
}

TEST(SortKey, AxisNormalsGetTheirCornerCells) {
  // The octant bits are the signs; the corner sub-triangle at x is 0 at every level.
  EXPECT_EQ(quantize_normal(vec3(1, 0, 0)), 0u);
  EXPECT_EQ(quantize_normal(vec3(0, 1, 0)), 0b000010101u);
  EXPECT_EQ(quantize_normal(vec3(0, 0, 1)), 0b000101010u);
  EXPECT_EQ(quantize_normal(vec3(-1, 0, 0)), 4u << 6);
  EXPECT_EQ(quantize_normal(vec3(0, 0, -1)), (1u << 6) | 0b101010u);
  // The octant's centre is in the middle triangle at every level.
  EXPECT_EQ(quantize_normal(vec3(1, 1, 1)), 0b000111111u);
  EXPECT_EQ(quantize_normal(vec3(-1, -1, -1)), 0b111111111u);
  // Magnitude does not matter; a zero vector gets a valid code.
  EXPECT_EQ(quantize_normal(vec3(0.3f, -2.0f, 0.7f)), quantize_normal(vec3(3.0f, -20.0f, 7.0f)));
  EXPECT_LT(quantize_normal(vec3(0.0f)), 512u);
}

TEST(SortKey, NormalCodeMatchesTheRecursiveSubdivision) {
  // The grid-and-bits implementation against the definition: equal but for normals within
  // float rounding of a cell border.
  std::mt19937 rng(7);
  int differ = 0;
  const int trials = 200000;
  for (int t = 0; t < trials; ++t) {
    vec3 n = test::random_unit(rng);
    differ += quantize_normal(n) != reference_normal_code(n);
  }
  EXPECT_LE(differ, trials / 10000);
  for (uint32_t c = 0; c < 512; ++c) EXPECT_EQ(reference_normal_code(decode_normal(c)), c);
}

TEST(SortKey, All512CodesDecodeToDistinctUnitVectorsInsideTheirOwnCells) {
  std::vector<vec3> centres;
  for (uint32_t c = 0; c < 512; ++c) {
    vec3 n = decode_normal(c);
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f) << c;
    EXPECT_EQ(quantize_normal(n), c) << "decoded centre of cell " << c << " falls in another cell";
    for (const vec3& other : centres) ASSERT_GT(angle(n, other), 0.01f) << c;
    centres.push_back(n);
  }
}

// Random unit normals: the cell a normal falls in has one of the nearest few centres (the
// central projection makes cells near the octant's corners ~5x smaller in solid angle than
// those at its centre, so the own centre is not always the very nearest), the centre is within
// the largest cell's radius, and every cell receives a reasonable share of the sphere.
TEST(SortKey, NormalCellsPartitionTheSphereReasonably) {
  std::vector<vec3> centres;
  for (uint32_t c = 0; c < 512; ++c) centres.push_back(decode_normal(c));
  std::mt19937 rng(5);
  const int samples = 512 * 400;
  std::vector<int> hits(512, 0);
  int worst_rank = 0, nearest = 0;
  float worst_angle = 0.0f;
  for (int s = 0; s < samples; ++s) {
    vec3 n = test::random_unit(rng);
    uint32_t code = quantize_normal(n);
    ++hits[code];
    float own = angle(n, centres[code]);
    worst_angle = std::max(worst_angle, own);
    int rank = 0;
    for (const vec3& c : centres) rank += angle(n, c) < own ? 1 : 0;
    worst_rank = std::max(worst_rank, rank);
    nearest += rank == 0;
  }
  EXPECT_LE(worst_rank, 5) << "own cell centre must be among the 6 nearest";
  EXPECT_GT(nearest, samples * 8 / 10) << "and mostly the nearest";
  EXPECT_LT(worst_angle, 0.18f) << "largest cell radius (rad), ~10 degrees";
  auto [lo, hi] = std::minmax_element(hits.begin(), hits.end());
  double mean = double(samples) / 512.0;
  EXPECT_GT(*lo, 0.25 * mean);
  EXPECT_LT(*hi, 3.0 * mean);
  RecordProperty("worst_rank", worst_rank);
  std::printf("normal cells: own centre nearest for %.1f%%, worst rank %d, largest radius %.4f rad, "
              "hits %.2f..%.2f of uniform\n", 100.0 * nearest / samples, worst_rank, worst_angle, *lo / mean, *hi / mean);
}

TEST(SortKey, NearbyNormalsGetEqualOrNeighbouringCodes) {
  std::mt19937 rng(6);
  int equal = 0;
  const int trials = 20000;
  float worst = 0.0f;
  for (int t = 0; t < trials; ++t) {
    vec3 n = test::random_unit(rng);
    vec3 m = glm::normalize(n + 0.005f * test::random_unit(rng));  // <= ~0.3 degrees away
    uint32_t a = quantize_normal(n), b = quantize_normal(m);
    if (a == b) ++equal;
    worst = std::max(worst, angle(decode_normal(a), decode_normal(b)));
  }
  // A normal 0.005 rad away crosses a cell border only when it lies that close to one.
  EXPECT_GT(equal, trials * 95 / 100);
  // Neighbouring cells: centres at most about two of the largest cell radii apart.
  EXPECT_LT(worst, 0.32f);
}

}  // namespace
}  // namespace sst
