#include "core/sampling/spherical_triangle.h"

#include <gtest/gtest.h>

#include "core/rng/hash_rng.h"

namespace sst {
namespace {

TEST(SphericalTriangle, SolidAngleOfAnOctantIsHalfPi) {
  // The triangle (1,0,0), (0,1,0), (0,0,1) seen from the origin covers one eighth of the sphere.
  EXPECT_NEAR(triangle_solid_angle(vec3(0), {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), kPi / 2.0f, 1e-5f);
}

TEST(SphericalTriangle, DirectionsAreUniformOverTheSolidAngle) {
  // Uniform in solid angle: the fraction of samples falling in each half of the triangle (split
  // along a median) equals that half's solid angle over the whole one.
  vec3 p(0.1f, -0.2f, 0.0f), v0(-1, -1, 1), v1(2, -1, 1.5f), v2(0, 2, 0.7f);
  vec3 mid = 0.5f * (v1 + v2);
  float whole = triangle_solid_angle(p, v0, v1, v2);
  float half = triangle_solid_angle(p, v0, v1, mid);
  HashRng rng = hash_rng(1, 1, 1);
  const int n = 200000;
  int in_first = 0;
  for (int i = 0; i < n; ++i) {
    vec2 b;
    float pdf;
    ASSERT_TRUE(sample_spherical_triangle(p, v0, v1, v2, vec2(hash_rng_next(rng), hash_rng_next(rng)), b, pdf));
    ASSERT_NEAR(pdf, 1.0f / whole, 1e-3f / whole);
    // The median from v0 to mid splits the triangle: b.x > b.y is the side of v1.
    if (b.x > b.y) ++in_first;
  }
  double expected = double(half) / whole;
  EXPECT_NEAR(double(in_first) / n, expected, 5.0 * std::sqrt(expected * (1 - expected) / n));
}

TEST(SphericalTriangle, DegenerateInputsAreRefused) {
  vec2 b;
  float pdf;
  EXPECT_FALSE(sample_spherical_triangle(vec3(0), vec3(0), {1, 0, 1}, {0, 1, 1}, vec2(0.5f), b, pdf));
  EXPECT_FALSE(sample_spherical_triangle(vec3(0), {1, 0, 1}, {2, 0, 2}, {3, 0, 3}, vec2(0.5f), b, pdf));
}

}  // namespace
}  // namespace sst
