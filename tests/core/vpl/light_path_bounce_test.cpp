// core/vpl/light_path_bounce.h: a bounce from outside the focus sphere sends its share of the
// directions into the cone of the sphere, yet weighted by its factor it integrates every region of
// the hemisphere as the cosine distribution does (so light paths stay unbiased); inside the sphere
// it is the cosine-weighted bounce it always was.
#include "core/vpl/light_path_bounce.h"

#include <gtest/gtest.h>

#include <array>
#include <functional>

#include "core/rng/hash_rng.h"
#include "tests/core/vpl/vpl_test_util.h"

namespace sst {
namespace {

using test::mean_error;
using test::MeanError;

TEST(LightPathBounce, WeightedDirectionsIntegrateTheCosineDistribution) {
  // A point 800 m from the focus (radius 10 m), its normal 37 degrees off the focus's direction.
  const vec3 center(0.0f), p(800.0f, 0.0f, 0.0f), ns = glm::normalize(vec3(-0.8f, 0.0f, 0.6f));
  const float radius = 10.0f, share = 0.5f;
  const vec3 axis = glm::normalize(center - p);
  const double sin2 = double(radius) * radius / (800.0 * 800.0);
  // Regions and their integrals of cos / pi: a cone about `axis` wholly above the surface holds
  // (axis . n) sin^2(theta_max); cos(theta) > 1/2 holds 3/4 of the cosine distribution; y > 0 half.
  struct Region {
    const char* name;
    std::function<bool(vec3)> inside;
    double integral;
  };
  const std::array<Region, 4> regions = {{
      {"hemisphere", [](vec3) { return true; }, 1.0},
      {"focus cone",
       [&](vec3 w) {
         const vec3 to = center - p;
         const vec3 c = glm::cross(w, to);
         return glm::dot(w, to) > 0.0f && glm::dot(c, c) <= radius * radius;
       },
       double(glm::dot(axis, ns)) * sin2},
      {"cos > 1/2", [&](vec3 w) { return glm::dot(w, ns) > 0.5f; }, 0.75},
      {"y > 0", [](vec3 w) { return w.y > 0.0f; }, 0.5},
  }};
  const int n = 400000;
  std::vector<std::vector<double>> values(regions.size(), std::vector<double>(size_t(n), 0.0));
  int aimed = 0;
  for (int i = 0; i < n; ++i) {
    HashRng rng = hash_rng(3, uint32_t(i), 0, 91);
    const vec2 u(hash_rng_next(rng), hash_rng_next(rng));
    vec3 wi(0.0f);
    float factor = 0.0f;
    if (!light_path_bounce(p, ns, u, center, radius, share, wi, factor)) continue;
    ASSERT_TRUE(std::isfinite(factor) && factor > 0.0f);
    aimed += regions[1].inside(wi) ? 1 : 0;
    for (size_t k = 0; k < regions.size(); ++k)
      if (regions[k].inside(wi)) values[k][size_t(i)] = double(factor);
  }
  EXPECT_NEAR(double(aimed) / n, share, 0.01) << "the share aimed at the focus";
  for (size_t k = 0; k < regions.size(); ++k) {
    const MeanError m = mean_error(values[k]);
    EXPECT_NEAR(m.mean, regions[k].integral, 5.0 * m.error + 1e-12) << regions[k].name;
    EXPECT_GT(m.error, 0.0) << regions[k].name << " was reached";
  }
}

TEST(LightPathBounce, InsideTheFocusOrWithoutOneIsTheCosineBounce) {
  const vec3 ns = glm::normalize(vec3(0.2f, -0.3f, 0.9f));
  const vec3 cosine = to_world(basis_from_normal(ns), sample_cosine_hemisphere(0.3f, 0.7f));
  struct Case {
    vec3 p;
    float radius, share;
  };
  for (const Case& c : {Case{vec3(3.0f, 0.0f, 0.0f), 5.0f, 0.5f}, Case{vec3(300.0f, 0.0f, 0.0f), 0.0f, 0.5f},
                        Case{vec3(300.0f, 0.0f, 0.0f), 5.0f, 0.0f}}) {
    vec3 wi(0.0f);
    float factor = 0.0f;
    ASSERT_TRUE(light_path_bounce(c.p, ns, vec2(0.3f, 0.7f), vec3(0.0f), c.radius, c.share, wi, factor));
    EXPECT_EQ(wi, cosine);
    EXPECT_EQ(factor, 1.0f);
  }
}

}  // namespace
}  // namespace sst
