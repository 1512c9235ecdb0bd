// VPL generation: the flux the VPLs carry, determinism, and extreme inputs.
#include "core/vpl/vpl_generator.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>

#include "core/scene/default_scene.h"
#include "core/vpl/vpl_clamp.h"
#include "core/vpl/vpl_shading.h"
#include "tests/analytic_scenes.h"
#include "tests/core/vpl/vpl_test_util.h"

namespace sst {
namespace {

using test::mean_error;
using test::PreparedScene;

VplParams params(int vpls, int max_bounces, int min_bounces) {
  VplParams p;
  p.vpls = vpls;
  p.vpl_max_bounces = max_bounces;
  p.vpl_min_bounces = min_bounces;
  return p;
}

void expect_all_finite(const VplSet& vpls) {
  for (const Vpl& v : vpls) {
    ASSERT_TRUE(is_finite(v.position) && is_finite(v.normal) && is_finite(v.intensity));
    ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
    ASSERT_GE(std::min(v.intensity.x, std::min(v.intensity.y, v.intensity.z)), 0.0f);
  }
}

// Sum over the VPLs of hit `hit` of intensity * pi: the flux that hit reflects.
dvec3 reflected_flux(const VplStats& stats, int hit) { return stats.intensity_per_bounce[size_t(hit)] * M_PI; }

const vec3 kAlbedo(0.7f, 0.5f, 0.3f);
const vec3 kLightPosition(0.2f, -0.3f, 0.1f);

// A closed box with a point light inside: every path hits a wall and, without roulette, keeps
// going, so hit k reflects exactly albedo^(k+1) times the light's flux 4 pi I, whatever the
// random numbers (the per-path weight is constant and each cosine bounce multiplies by albedo).
TEST(VplFlux, ClosedBoxReflectsAlbedoPowersOfThePointLightFluxExactly) {
  Scene scene = test::diffuse_box(kAlbedo, 2.0f);
  const vec3 intensity(1.0f, 2.0f, 0.5f);
  scene.lights.push_back(test::punctual_light(LightType::Point, kLightPosition, {0, 0, -1}, intensity));
  PreparedScene p(std::move(scene));
  const int hits = 4;
  VplStats stats;
  VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, params(4000 * hits, hits, 100), 3, true, &stats);
  ASSERT_EQ(vpls.size(), size_t(4000 * hits));
  EXPECT_EQ(stats.paths, 4000u);
  EXPECT_EQ(stats.rays, stats.paths_traced * hits);  // no path escapes the box or is cut short
  EXPECT_GE(stats.paths_traced, stats.paths);
  nlohmann::json j = to_json(stats);
  EXPECT_EQ(j["vpls"], 4000 * hits);
  EXPECT_EQ(j["intensity_per_bounce"].size(), size_t(hits));
  expect_all_finite(vpls);
  for (int k = 0; k < hits; ++k) {
    EXPECT_EQ(stats.vpls_per_bounce[size_t(k)], 4000u);
    for (int c = 0; c < 3; ++c) {
      double expected = std::pow(double(kAlbedo[c]), k + 1) * 4.0 * M_PI * intensity[c];
      EXPECT_NEAR(reflected_flux(stats, k)[c], expected, 1e-4 * expected) << "hit " << k << " channel " << c;
    }
  }
}

struct FluxCase {
  const char* name;
  LightType type;
  int min_bounces;  // 100: no roulette
};

class VplFluxStatistical : public ::testing::TestWithParam<FluxCase> {};

// With a spot light (random weights) and/or Russian roulette (random path lengths) the reflected
// flux per hit is albedo^(k+1) * flux in expectation: tested over independent seeds.
TEST_P(VplFluxStatistical, ExpectedReflectedFluxIsAlbedoPowersOfTheLightFlux) {
  const FluxCase fc = GetParam();
  Scene scene = test::diffuse_box(kAlbedo, 2.0f);
  PunctualLight light = test::punctual_light(fc.type, kLightPosition, {0.2f, 0.1f, -1.0f}, vec3(2.0f));
  light.cos_inner = std::cos(0.3f);
  light.cos_outer = std::cos(0.9f);
  scene.lights.push_back(light);
  PreparedScene p(std::move(scene));
  const double flux = fc.type == LightType::Point ? 4.0 * M_PI * 2.0 : 2.0 * test::spot_flux_per_intensity(light);
  const int hits = 5, seeds = 24;
  std::vector<double> per_hit[hits][3];
  for (uint32_t seed = 0; seed < uint32_t(seeds); ++seed) {
    VplStats stats;
    VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, params(6000, hits, fc.min_bounces), seed, true, &stats);
    ASSERT_EQ(vpls.size(), 6000u);
    expect_all_finite(vpls);
    for (int k = 0; k < hits; ++k)
      for (int c = 0; c < 3; ++c) per_hit[k][c].push_back(reflected_flux(stats, k)[c]);
  }
  for (int k = 0; k < hits; ++k)
    for (int c = 0; c < 3; ++c) {
      auto m = mean_error(per_hit[k][c]);
      double expected = std::pow(double(kAlbedo[c]), k + 1) * flux;
      EXPECT_NEAR(m.mean, expected, 5.0 * m.error + 1e-4 * expected) << fc.name << " hit " << k << " channel " << c;
    }
}

INSTANTIATE_TEST_SUITE_P(VplLights, VplFluxStatistical,
                         ::testing::Values(FluxCase{"spot", LightType::Spot, 100},
                                           FluxCase{"point_roulette", LightType::Point, 1},
                                           FluxCase{"spot_roulette", LightType::Spot, 2}),
                         [](const auto& info) { return std::string(info.param.name); });

// A directional light over an open plane of half-size h: the plane intercepts E * 4 h^2 |d.z|.
TEST(VplFlux, DirectionalLightOnAnOpenPlaneReflectsAlbedoTimesInterceptedFlux) {
  const float albedo = 0.6f, half = 1.0f, e = 2.0f;
  const vec3 dir = glm::normalize(vec3(0.3f, 0.2f, -1.0f));
  Scene scene = test::lambert_plane(albedo, half, 5.0f, 1.0f);
  scene.lights.push_back(test::punctual_light(LightType::Directional, vec3(0), dir, vec3(e)));
  PreparedScene p(std::move(scene));
  std::vector<double> flux;
  for (uint32_t seed = 0; seed < 16; ++seed) {
    VplStats stats;
    VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, params(5000, 3, 100), seed, true, &stats);
    ASSERT_EQ(vpls.size(), 5000u);
    expect_all_finite(vpls);
    flux.push_back(reflected_flux(stats, 0).x);
    EXPECT_EQ(stats.vpls_per_bounce[1], 0u);  // an open plane: nothing to bounce to
  }
  auto m = mean_error(flux);
  double expected = albedo * e * 4.0 * half * half * -dir.z;
  EXPECT_NEAR(m.mean, expected, 5.0 * m.error + 1e-4 * expected);
}

// Every wall of a box emits Le from both sides; the inner sides emit Le pi A (A = 24) into the
// box, the outer sides emit as much into the void. The first hit reflects albedo Le pi A.
TEST(VplFlux, DoubleSidedEmittersSendHalfTheirFluxEachWay) {
  const float albedo = 0.5f, le = 1.5f;
  PreparedScene p(test::emissive_box(albedo, le, 2.0f));
  std::vector<double> flux;
  for (uint32_t seed = 0; seed < 16; ++seed) {
    VplStats stats;
    generate_vpls(p.scene, *p.accel, *p.lights, params(5000, 1, 100), seed, true, &stats);
    flux.push_back(reflected_flux(stats, 0).x);
  }
  auto m = mean_error(flux);
  double expected = albedo * le * M_PI * 24.0;
  EXPECT_NEAR(m.mean, expected, 5.0 * m.error + 1e-4 * expected);
}

// The first-hit flux does not depend on the scene's scale (lengths enter only through offsets).
TEST(VplExtremes, SceneScaleKeepsFluxAndFiniteVpls) {
  for (float scale : {1e-3f, 1.0f, 1e4f}) {
    Scene scene = test::diffuse_box(kAlbedo, 2.0f);
    scene.lights.push_back(test::punctual_light(LightType::Point, kLightPosition, {0, 0, -1}, vec3(1.0f)));
    test::scale_scene(scene, scale);
    PreparedScene p(std::move(scene));
    VplStats stats;
    VplParams pr = params(3000, 3, 100);
    pr.clamp_relative_to = "vpl_bounds";
    pr.clamp_fraction = 0.01f;
    VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, pr, 5, true, &stats);
    ASSERT_EQ(vpls.size(), 3000u) << "scale " << scale;
    expect_all_finite(vpls);
    for (const Vpl& v : vpls) {
      ASSERT_LE(max_component(glm::abs(v.position)), 1.0001f * scale) << "scale " << scale;
    }
    double expected = kAlbedo.x * 4.0 * M_PI;
    EXPECT_NEAR(reflected_flux(stats, 0).x, expected, 1e-4 * expected) << "scale " << scale;
    // D = the VPL bounds' diagonal: nearly the box's 2 sqrt(3) * scale with thousands of VPLs.
    EXPECT_GT(stats.clamp_distance, 0.9f * 0.01f * std::sqrt(12.0f) * scale);
    EXPECT_LE(stats.clamp_distance, 1.0001f * 0.01f * std::sqrt(12.0f) * scale);
    EXPECT_EQ(stats.clamp_per_depth, 0.0f);
  }
}

// By default the clamp follows the camera: no fixed part, clamp_fraction per unit of depth.
TEST(VplClamp, CameraDistanceClampHasNoFixedPart) {
  PreparedScene p(load_default_scene());
  VplStats stats;
  VplParams pr = params(100, 8, 3);
  pr.clamp_fraction = 0.25f;
  generate_vpls(p.scene, *p.accel, *p.lights, pr, 1, true, &stats);
  EXPECT_EQ(stats.clamp_distance, 0.0f);
  EXPECT_EQ(stats.clamp_per_depth, 0.25f);
  EXPECT_FLOAT_EQ(vpl_clamp_at(stats.clamp_distance, stats.clamp_per_depth, 4.0f), 1.0f);
  EXPECT_FLOAT_EQ(vpl_clamp_at(0.5f, 0.0f, 4.0f), 0.5f) << "vpl_bounds: the set's c wherever the point";
}

TEST(VplDeterminism, SameSeedSameBitsWhateverTheThreadCount) {
  PreparedScene p(load_default_scene());
  VplParams pr = params(20000, 8, 3);
  auto run = [&](int threads, uint32_t seed) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    return generate_vpls(p.scene, *p.accel, *p.lights, pr, seed, false, nullptr);
  };
  VplSet one = run(1, 9), two = run(2, 9), other = run(2, 10);
  ASSERT_EQ(one.size(), 20000u);
  ASSERT_EQ(two.size(), one.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(Vpl)), 0);
  ASSERT_EQ(other.size(), one.size());
  EXPECT_NE(std::memcmp(one.data(), other.data(), one.size() * sizeof(Vpl)), 0);
  expect_all_finite(one);
}

// Path i is a function of (seed, i) alone: a larger set starts with the same VPL positions.
TEST(VplDeterminism, LargerCountsExtendTheSamePaths) {
  PreparedScene p(load_default_scene());
  VplSet small = generate_vpls(p.scene, *p.accel, *p.lights, params(3000, 8, 3), 4, true, nullptr);
  VplSet large = generate_vpls(p.scene, *p.accel, *p.lights, params(50000, 8, 3), 4, true, nullptr);
  ASSERT_EQ(small.size(), 3000u);
  for (size_t i = 0; i < small.size(); ++i) {
    ASSERT_EQ(small[i].position, large[i].position) << i;
    ASSERT_EQ(small[i].normal, large[i].normal) << i;
  }
}

TEST(VplExtremes, NoLightsGiveAnEmptySet) {
  PreparedScene p(test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f));
  VplStats stats;
  VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, params(1000, 8, 3), 1, true, &stats);
  EXPECT_TRUE(vpls.empty());
  EXPECT_EQ(stats.paths, 0u);
  EXPECT_EQ(stats.rays, 0u);
  EXPECT_FALSE(stats.path_limit_reached);
}

// Black surfaces deposit no VPL (a zero-intensity VPL only costs shading time) and end the path;
// generation stops at the path limit instead of tracing forever.
TEST(VplExtremes, BlackSurfacesDepositNothingAndGenerationEnds) {
  Scene scene = test::diffuse_box(vec3(0.0f), 2.0f);
  scene.lights.push_back(test::punctual_light(LightType::Point, kLightPosition, {0, 0, -1}, vec3(1.0f)));
  PreparedScene p(std::move(scene));
  VplStats stats;
  VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, params(100, 8, 3), 1, true, &stats);
  EXPECT_TRUE(vpls.empty());
  EXPECT_TRUE(stats.path_limit_reached);
  EXPECT_EQ(stats.paths, kMaxPathsPerVpl * 100);
  EXPECT_EQ(stats.rays, kMaxPathsPerVpl * 100);
}

// Metals have no diffuse part: in full-BRDF mode they deposit nothing; diffuse_only uses baseColor.
TEST(VplExtremes, FullBrdfModeUsesTheDiffusePartOfTheAlbedo) {
  Scene scene = test::diffuse_box(vec3(0.8f), 2.0f);
  scene.materials[0].metallic = 0.25f;
  scene.lights.push_back(test::punctual_light(LightType::Point, kLightPosition, {0, 0, -1}, vec3(1.0f)));
  PreparedScene p(std::move(scene));
  VplStats full, diffuse;
  generate_vpls(p.scene, *p.accel, *p.lights, params(2000, 1, 100), 1, false, &full);
  generate_vpls(p.scene, *p.accel, *p.lights, params(2000, 1, 100), 1, true, &diffuse);
  EXPECT_NEAR(reflected_flux(full, 0).x, 0.75 * 0.8 * 4.0 * M_PI, 1e-5 * 4.0 * M_PI);
  EXPECT_NEAR(reflected_flux(diffuse, 0).x, 0.8 * 4.0 * M_PI, 1e-5 * 4.0 * M_PI);
}

TEST(VplExtremes, OneTwoAndThreeVpls) {
  PreparedScene p(load_default_scene());
  for (int n : {1, 2, 3}) {
    VplStats stats;
    VplParams pr = params(n, 8, 3);
    pr.clamp_relative_to = "vpl_bounds";
    VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, pr, 2, false, &stats);
    ASSERT_EQ(vpls.size(), size_t(n));
    EXPECT_GE(stats.paths, 1u);
    expect_all_finite(vpls);
    EXPECT_GT(stats.clamp_distance, 0.0f);
    EXPECT_TRUE(std::isfinite(stats.clamp_distance));
  }
}

TEST(VplParamsCheck, BadValuesNameTheParameter) {
  PreparedScene p(load_default_scene());
  auto message = [&](VplParams pr) {
    try {
      generate_vpls(p.scene, *p.accel, *p.lights, pr, 0, true, nullptr);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message(params(0, 8, 3)).find("vpls"), std::string::npos);
  EXPECT_NE(message(params(-5, 8, 3)).find("vpls"), std::string::npos);
  EXPECT_NE(message(params(100, 0, 3)).find("vpl_max_bounces"), std::string::npos);
  EXPECT_NE(message(params(100, 8, -1)).find("vpl_min_bounces"), std::string::npos);
  VplParams bad_clamp = params(100, 8, 3);
  bad_clamp.clamp_fraction = -0.1f;
  EXPECT_NE(message(bad_clamp).find("clamp_fraction"), std::string::npos);
  bad_clamp.clamp_fraction = NAN;
  EXPECT_NE(message(bad_clamp).find("clamp_fraction"), std::string::npos);
  bad_clamp.clamp_fraction = 0.1f;
  bad_clamp.clamp_relative_to = "scene";
  EXPECT_NE(message(bad_clamp).find("clamp_relative_to"), std::string::npos);
  bad_clamp.clamp_relative_to = "camera_distance";
  bad_clamp.directional_focus = -1.0f;
  EXPECT_NE(message(bad_clamp).find("directional_focus"), std::string::npos);
  bad_clamp.directional_focus = 2.0f;
  for (float share : {-0.1f, 1.0f, float(NAN)}) {
    bad_clamp.focus_bounces = share;  // 1 would leave the rest of the hemisphere undrawn: biased
    EXPECT_NE(message(bad_clamp).find("focus_bounces"), std::string::npos) << share;
  }
}

TEST(VplParamsCheck, JsonRoundTripListsEveryField) {
  VplParams pr = params(123, 4, 2);
  pr.clamp_fraction = 0.02f;
  nlohmann::json j = params_to_json(pr);
  VplParams back;
  params_from_json(back, j, "test");
  EXPECT_EQ(back.vpls, 123);
  EXPECT_EQ(back.vpl_max_bounces, 4);
  EXPECT_EQ(back.vpl_min_bounces, 2);
  EXPECT_FLOAT_EQ(back.clamp_fraction, 0.02f);
  EXPECT_THROW(params_from_json(back, nlohmann::json{{"vpl", 3}}, "test"), Error);
}

TEST(VplClamp, UsesTheVplBoundsAndFallsBackToTheSceneForOnePoint) {
  Scene scene = test::lambert_plane(0.5f, 10.0f, 5.0f, 1.0f);  // diagonal sqrt(800)
  VplSet vpls(2);
  vpls[0].position = vec3(0, 0, 0);
  vpls[1].position = vec3(3, 4, 0);
  EXPECT_FLOAT_EQ(vpl_clamp_distance(0.01f, vpls, scene), 0.05f);
  vpls.resize(1);
  EXPECT_NEAR(vpl_clamp_distance(0.01f, vpls, scene), 0.01f * std::sqrt(800.0f), 1e-5f);
  EXPECT_NEAR(vpl_clamp_distance(0.01f, {}, scene), 0.01f * std::sqrt(800.0f), 1e-5f);
  EXPECT_EQ(vpl_clamp_distance(0.01f, {}, Scene{}), 0.0f);
}

}  // namespace
}  // namespace sst
