#include "core/sampling/sampling.h"

#include <gtest/gtest.h>

#include "core/rng/hash_rng.h"
#include "core/sampling/discrete_distribution.h"
#include "tests/stat_util.h"

namespace sst {
namespace {

TEST(DiscreteDistribution, FrequenciesMatchPmf) {
  std::vector<double> weights = {1.0, 0.0, 3.0, 0.5, 0.0, 10.0, 2.5};
  DiscreteDistribution d(weights);
  double total = 17.0;
  double sum = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    EXPECT_NEAR(d.pmf(i), weights[i] / total, 1e-7);
    sum += d.pmf(i);
  }
  EXPECT_NEAR(sum, 1.0, 1e-6);
  const int n = 200000;
  std::vector<double> observed(weights.size(), 0.0), expected(weights.size());
  HashRng rng = hash_rng(3, 0, 0);
  for (int i = 0; i < n; ++i) observed[d.sample(hash_rng_next(rng))] += 1.0;
  for (size_t i = 0; i < weights.size(); ++i) expected[i] = n * weights[i] / total;
  EXPECT_EQ(observed[1], 0.0);
  EXPECT_EQ(observed[4], 0.0);
  int dof;
  double chi2 = test::chi_square_statistic(observed, expected, &dof);
  EXPECT_LT(chi2, test::chi_square_critical_1e6(dof));
}

TEST(DiscreteDistribution, EdgeCases) {
  DiscreteDistribution empty(std::vector<double>{0.0, 0.0});
  EXPECT_TRUE(empty.empty());
  DiscreteDistribution bad(std::vector<double>{NAN, -1.0, 2.0, INFINITY});
  EXPECT_EQ(bad.sample(0.0f), 2u);
  EXPECT_EQ(bad.sample(0.9999999f), 2u);
  DiscreteDistribution trailing(std::vector<double>{1.0, 0.0, 0.0});
  EXPECT_EQ(trailing.sample(0.99999994f), 0u);
}

TEST(Sampling, CosineHemisphereMatchesItsPdf) {
  // Bin cos(theta) into 20 bins: P(bin) = integral of 2 cos sin dtheta = c1^2 - c0^2.
  const int n = 200000, bins = 20;
  std::vector<double> observed(bins, 0.0), expected(bins);
  HashRng rng = hash_rng(5, 1, 2);
  for (int i = 0; i < n; ++i) {
    vec3 w = sample_cosine_hemisphere(hash_rng_next(rng), hash_rng_next(rng));
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
    ASSERT_GE(w.z, 0.0f);
    observed[std::min(bins - 1, int(w.z * bins))] += 1.0;
  }
  for (int b = 0; b < bins; ++b) {
    double c0 = double(b) / bins, c1 = double(b + 1) / bins;
    expected[b] = n * (c1 * c1 - c0 * c0);
  }
  int dof;
  double chi2 = test::chi_square_statistic(observed, expected, &dof);
  EXPECT_LT(chi2, test::chi_square_critical_1e6(dof));
}

TEST(Sampling, UniformSphereAndTriangle) {
  HashRng rng = hash_rng(9, 9, 9);
  vec3 mean(0.0f);
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    vec3 w = sample_uniform_sphere(hash_rng_next(rng), hash_rng_next(rng));
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
    mean += w;
  }
  mean /= float(n);
  // Each coordinate has variance 1/3; 6 standard errors.
  EXPECT_LT(glm::length(mean), 6.0f * std::sqrt(1.0f / 3.0f / n) * std::sqrt(3.0f));
  vec2 centroid(0.0f);
  for (int i = 0; i < n; ++i) {
    vec2 b = sample_uniform_triangle(hash_rng_next(rng), hash_rng_next(rng));
    ASSERT_GE(b.x, 0.0f);
    ASSERT_GE(b.y, 0.0f);
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    centroid += b;
  }
  centroid /= float(n);
  EXPECT_NEAR(centroid.x, 1.0f / 3.0f, 0.005f);
  EXPECT_NEAR(centroid.y, 1.0f / 3.0f, 0.005f);
}

TEST(Sampling, PowerHeuristic) {
  EXPECT_FLOAT_EQ(power_heuristic(1.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(power_heuristic(3.0f, 1.0f), 0.9f);
  EXPECT_EQ(power_heuristic(0.0f, 0.0f), 0.0f);
}

}  // namespace
}  // namespace sst
