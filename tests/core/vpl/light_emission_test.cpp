// LightSampler::sample_emission: the mean weight of emission samples is the lights' total power
// (flux), and positions and directions follow the stated distributions.
#include <gtest/gtest.h>

#include <array>

#include "core/rng/hash_rng.h"
#include "tests/stat_util.h"
#include "tests/analytic_scenes.h"
#include "tests/core/vpl/vpl_test_util.h"

namespace sst {
namespace {

using test::mean_error;
using test::MeanError;
using test::PreparedScene;

EmissionSample draw(const LightSampler& lights, uint32_t i, bool* ok) {
  HashRng rng = hash_rng(11, i, 0, 77);
  float u_pick = hash_rng_next(rng);
  vec2 u_pos(hash_rng_next(rng), hash_rng_next(rng)), u_dir(hash_rng_next(rng), hash_rng_next(rng));
  EmissionSample e;
  *ok = lights.sample_emission(u_pick, u_pos, u_dir, e);
  return e;
}

// Mean weight per channel over n samples; failed samples count as zero.
std::array<MeanError, 3> weight_moments(const LightSampler& lights, int n) {
  std::vector<double> w[3];
  for (int i = 0; i < n; ++i) {
    bool ok = false;
    EmissionSample e = draw(lights, uint32_t(i), &ok);
    for (int c = 0; c < 3; ++c) w[c].push_back(ok ? double(e.weight[c]) : 0.0);
  }
  return {mean_error(w[0]), mean_error(w[1]), mean_error(w[2])};
}

// Chi-square of the histogram of values in [0, 1) against a uniform distribution.
void expect_uniform(const std::vector<double>& values, const char* what) {
  const int bins = 20;
  std::vector<double> observed(bins, 0.0), expected(bins, double(values.size()) / bins);
  for (double v : values) observed[std::clamp(int(v * bins), 0, bins - 1)] += 1.0;
  int dof = 0;
  double chi2 = test::chi_square_statistic(observed, expected, &dof);
  EXPECT_LT(chi2, test::chi_square_critical_1e6(dof)) << what;
}

TEST(LightEmission, PointLightCarriesFourPiIAndIsUniformOverTheSphere) {
  Scene scene = test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f);
  const vec3 intensity(3.0f, 2.0f, 0.5f), position(0.1f, 0.2f, 0.7f);
  scene.lights.push_back(test::punctual_light(LightType::Point, position, {0, 0, -1}, intensity));
  PreparedScene p(std::move(scene));
  std::vector<double> z, phi;
  for (uint32_t i = 0; i < 100000; ++i) {
    bool ok = false;
    EmissionSample e = draw(*p.lights, i, &ok);
    ASSERT_TRUE(ok);
    // One light, constant intensity: every sample carries exactly the flux 4 pi I.
    EXPECT_NEAR(e.weight.x, 4.0 * M_PI * intensity.x, 1e-5 * 4.0 * M_PI * intensity.x);
    EXPECT_NEAR(e.weight.z, 4.0 * M_PI * intensity.z, 1e-5 * 4.0 * M_PI * intensity.z);
    EXPECT_EQ(e.position, position);
    EXPECT_EQ(e.normal, vec3(0.0f));
    EXPECT_NEAR(glm::length(e.direction), 1.0f, 1e-5f);
    z.push_back(0.5 * (e.direction.z + 1.0));  // uniform on the sphere: z uniform in [-1, 1]
    phi.push_back((std::atan2(e.direction.y, e.direction.x) + M_PI) / (2.0 * M_PI));
  }
  expect_uniform(z, "cos theta");
  expect_uniform(phi, "phi");
}

TEST(LightEmission, SpotLightCarriesItsConeFluxAndStaysInTheCone) {
  Scene scene = test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f);
  PunctualLight spot = test::punctual_light(LightType::Spot, {0, 0, 1}, {0.3f, -0.2f, -1.0f}, vec3(5.0f));
  spot.cos_inner = std::cos(0.4f);
  spot.cos_outer = std::cos(0.7f);
  scene.lights.push_back(spot);
  PreparedScene p(std::move(scene));
  for (uint32_t i = 0; i < 20000; ++i) {
    bool ok = false;
    EmissionSample e = draw(*p.lights, i, &ok);
    if (ok) {
      EXPECT_GE(glm::dot(e.direction, spot.direction), spot.cos_outer - 1e-5f);
    }
  }
  auto m = weight_moments(*p.lights, 400000);
  double flux = 5.0 * test::spot_flux_per_intensity(spot);
  EXPECT_NEAR(m[0].mean, flux, 5.0 * m[0].error + 1e-4 * flux);
}

TEST(LightEmission, DirectionalLightCarriesIrradianceTimesTheBoundingDisc) {
  Scene scene = test::lambert_plane(0.5f, 2.0f, 5.0f, 1.0f);
  const vec3 dir = glm::normalize(vec3(0.3f, 0.2f, -1.0f));
  scene.lights.push_back(test::punctual_light(LightType::Directional, vec3(0), dir, vec3(2.0f)));
  PreparedScene p(std::move(scene));
  const Bounds3& b = p.scene.bounds;
  const float r = 0.5f * b.diagonal();
  std::vector<double> radius2;
  for (uint32_t i = 0; i < 50000; ++i) {
    bool ok = false;
    EmissionSample e = draw(*p.lights, i, &ok);
    ASSERT_TRUE(ok);
    EXPECT_NEAR(e.weight.x, 2.0 * M_PI * r * r, 1e-5 * 2.0 * M_PI * r * r);
    EXPECT_EQ(e.direction, p.scene.lights[0].direction);
    vec3 rel = e.position - b.center();
    float along = glm::dot(rel, dir);
    EXPECT_NEAR(along, -1.01f * r, 1e-4f * r);  // upstream, outside the bounding sphere
    vec3 across = rel - along * dir;
    radius2.push_back(double(glm::dot(across, across)) / double(r * r));  // uniform disc: rho^2 uniform
  }
  expect_uniform(radius2, "disc radius^2");
}

// With a focus, a directional light's start points crowd around the focus (half of them within
// its first disc) but every region of the plane still receives E x its area in expectation: the
// flux through a small disc at the focus, through rings across the discs' edges and far from the
// focus, and the total.
TEST(LightEmission, DirectionalFocusKeepsTheFluxOfEveryRegion) {
  Scene scene = test::lambert_plane(0.5f, 400.0f, 5.0f, 1.0f);
  const vec3 dir = glm::normalize(vec3(0.3f, 0.2f, -1.0f));
  scene.lights.push_back(test::punctual_light(LightType::Directional, vec3(0), dir, vec3(2.0f)));
  PreparedScene p(std::move(scene));
  const float r = 0.5f * p.scene.bounds.diagonal();
  EmissionFocus focus{vec3(30.0f, -20.0f, 1.0f), 1.0f};  // discs of 1, 4, 16, 64, 256 m, then the scene's
  ASSERT_EQ(focus_disc_count(focus.radius, r), 5);
  // The regions, as [inner, outer) distances from the focus's line, and their areas.
  const std::array<std::pair<double, double>, 4> rings = {{{0.0, 0.5}, {3.0, 5.0}, {60.0, 70.0}, {300.0, 350.0}}};
  const int n = 400000;
  std::vector<std::vector<double>> flux(rings.size() + 1, std::vector<double>(size_t(n), 0.0));
  int in_first = 0;
  for (int i = 0; i < n; ++i) {
    HashRng rng = hash_rng(5, uint32_t(i), 0, 78);
    float u_pick = hash_rng_next(rng);
    vec2 u_pos(hash_rng_next(rng), hash_rng_next(rng)), u_dir(hash_rng_next(rng), hash_rng_next(rng));
    EmissionSample e;
    ASSERT_TRUE(p.lights->sample_emission(u_pick, u_pos, u_dir, e, focus));
    vec3 rel = e.position - focus.center;
    vec3 across = rel - glm::dot(rel, dir) * dir;
    double rho = double(glm::length(across));
    in_first += rho < 1.0 ? 1 : 0;
    for (size_t k = 0; k < rings.size(); ++k)
      if (rho >= rings[k].first && rho < rings[k].second) flux[k][size_t(i)] = double(e.weight.x);
    flux[rings.size()][size_t(i)] = double(e.weight.x);
  }
  EXPECT_NEAR(double(in_first) / n, 0.5, 0.01) << "half of the paths start in the first disc";
  for (size_t k = 0; k <= rings.size(); ++k) {
    double area = k < rings.size() ? M_PI * (rings[k].second * rings[k].second - rings[k].first * rings[k].first)
                                   : M_PI * double(r) * double(r);
    MeanError m = mean_error(flux[k]);
    EXPECT_NEAR(m.mean, 2.0 * area, 5.0 * m.error) << "region " << k << ": E x area";
    EXPECT_GT(m.error, 0.0) << "region " << k << " was reached";
  }
}

class LightEmissionTriangle : public ::testing::TestWithParam<bool> {};

// An emitter of radiance Le and area A emits Le pi A from each emitting side.
TEST_P(LightEmissionTriangle, CarriesLePiAPerSideAndLeavesCosineDistributed) {
  const bool double_sided = GetParam();
  Scene scene = test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f);
  const vec3 a(0, 0, 1), b(1, 0, 1.2f), c(0, 1.5f, 1.1f), le(2.0f, 1.0f, 0.25f);
  test::add_emissive_triangle(scene, a, b, c, le, double_sided);
  PreparedScene p(std::move(scene));
  const vec3 n = glm::normalize(glm::cross(b - a, c - a));
  const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
  const double flux = M_PI * area * le.x * (double_sided ? 2.0 : 1.0);
  std::vector<double> cos2;
  int back = 0, n_samples = 100000;
  for (uint32_t i = 0; i < uint32_t(n_samples); ++i) {
    bool ok = false;
    EmissionSample e = draw(*p.lights, i, &ok);
    ASSERT_TRUE(ok);
    EXPECT_NEAR(e.weight.x, flux, 1e-4 * flux);
    EXPECT_NEAR(glm::dot(e.position - a, n), 0.0f, 1e-5f);
    float side = glm::dot(e.normal, n);
    EXPECT_NEAR(std::abs(side), 1.0f, 1e-5f);
    if (side < 0.0f) ++back;
    float cos_t = glm::dot(e.direction, e.normal);
    EXPECT_GT(cos_t, 0.0f);
    cos2.push_back(double(cos_t) * cos_t);  // cosine-weighted: cos^2 uniform in [0, 1]
  }
  expect_uniform(cos2, "cos^2 theta");
  if (double_sided) {
    EXPECT_NEAR(back, n_samples / 2, 5.0 * std::sqrt(n_samples * 0.25));
  } else {
    EXPECT_EQ(back, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(LightEmissionSides, LightEmissionTriangle, ::testing::Values(false, true));

TEST(LightEmission, MeanWeightOfMixedLightsIsTheirTotalPower) {
  Scene scene = test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f);
  const vec3 ip(1.0f, 0.5f, 0.2f), is(3.0f, 3.0f, 1.0f), e_dir(0.5f, 0.7f, 1.0f);
  scene.lights.push_back(test::punctual_light(LightType::Point, {0.2f, 0, 1}, {0, 0, -1}, ip));
  PunctualLight spot = test::punctual_light(LightType::Spot, {0, 0.3f, 2}, {0, 0, -1}, is);
  spot.cos_inner = std::cos(0.2f);
  spot.cos_outer = std::cos(0.5f);
  scene.lights.push_back(spot);
  scene.lights.push_back(test::punctual_light(LightType::Directional, vec3(0), {0.1f, 0, -1}, e_dir));
  const vec3 le1(4.0f, 2.0f, 1.0f), le2(0.5f, 1.0f, 3.0f);
  test::add_emissive_triangle(scene, {0, 0, 1}, {0.5f, 0, 1}, {0, 0.5f, 1.2f}, le1, false);
  test::add_emissive_triangle(scene, {-1, 0, 0.5f}, {-1, 0.3f, 0.5f}, {-0.7f, 0, 0.6f}, le2, true);
  PreparedScene p(std::move(scene));
  auto tri_area = [&](uint32_t t) {
    const uvec3& v = p.scene.triangles[t];
    return 0.5 * glm::length(glm::cross(p.scene.positions[v.y] - p.scene.positions[v.x],
                                        p.scene.positions[v.z] - p.scene.positions[v.x]));
  };
  const double r = 0.5 * p.scene.bounds.diagonal();
  const double spot_k = test::spot_flux_per_intensity(spot);
  auto m = weight_moments(*p.lights, 400000);
  for (int c = 0; c < 3; ++c) {
    double flux = 4.0 * M_PI * ip[c] + spot_k * is[c] + M_PI * r * r * e_dir[c] +
                  M_PI * tri_area(2) * le1[c] + 2.0 * M_PI * tri_area(3) * le2[c];
    EXPECT_NEAR(m[c].mean, flux, 5.0 * m[c].error + 1e-4 * flux) << "channel " << c;
  }
}

TEST(LightEmission, NoLightsOrAZeroConeGivesNoSample) {
  PreparedScene empty(test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f));
  EmissionSample e;
  EXPECT_FALSE(empty.lights->sample_emission(0.5f, vec2(0.5f), vec2(0.5f), e));
  Scene scene = test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f);
  PunctualLight spot = test::punctual_light(LightType::Spot, {0, 0, 1}, {0, 0, -1}, vec3(1.0f));
  spot.cos_inner = spot.cos_outer = 1.0f;
  scene.lights.push_back(spot);
  PreparedScene zero_cone(std::move(scene));
  for (uint32_t i = 0; i < 100; ++i) {
    bool ok = true;
    draw(*zero_cone.lights, i, &ok);
    EXPECT_FALSE(ok);
  }
}

}  // namespace
}  // namespace sst
