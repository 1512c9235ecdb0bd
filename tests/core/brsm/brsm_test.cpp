// BRSM VPLs (core/brsm/brsm.h): how the maps share the VPLs, the set's expected flux, determinism,
// extreme inputs, and per image block on the Cornell box and the breakfast room: the one-bounce
// light of BRSM VPLs equals that of path VPLs and the path tracer's.
#include "core/brsm/brsm_generator.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>
#include <filesystem>

#include "core/pipeline/renderer.h"
#include "core/render/camera.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "tests/analytic_scenes.h"
#include "tests/core/vpl/vpl_test_util.h"
#include "tests/stat_util.h"
#include "tests/test_util.h"

namespace sst {
namespace {

using test::PreparedScene;

VplParams brsm_params(int vpls, int resolution) {
  VplParams p;
  p.vpl_source = "brsm";
  p.vpls = vpls;
  p.brsm_resolution = resolution;
  return p;
}

glsl::ViewParams scene_view(const Scene& scene, int width, int height) {
  PinholeCamera camera(select_camera(scene, ""), width, height);
  return view_params(camera, width, height, 0);
}

dvec3 intensity_sum(const VplSet& vpls) {
  dvec3 sum(0.0);
  for (const Vpl& v : vpls) sum += dvec3(v.intensity);
  return sum;
}

void expect_all_finite(const VplSet& vpls) {
  for (const Vpl& v : vpls) {
    ASSERT_TRUE(is_finite(v.position) && is_finite(v.normal) && is_finite(v.intensity));
    ASSERT_GT(max_component(v.intensity), 0.0f);
  }
}

TEST(BrsmMaps, OneMapPerLightWhenFewAndRunsOfEqualPowerWhenMany) {
  PreparedScene few(test::many_lights(5, 0, 3, 0, false));
  std::vector<BrsmMap> maps = brsm_maps(few.lights->packed(), 1000, 8);
  ASSERT_EQ(maps.size(), 3u);
  uint32_t total = 0;
  for (size_t k = 0; k < maps.size(); ++k) {
    EXPECT_EQ(maps[k].end_light, maps[k].first_light + 1);
    EXPECT_EQ(maps[k].vpl_offset, total);
    EXPECT_NEAR(double(maps[k].vpl_count), 1000.0 * maps[k].pmf_sum, 2.0);
    total += maps[k].vpl_count;
  }
  EXPECT_EQ(total, 1000u);

  PreparedScene many(test::many_lights(5, 300, 4, 3, true));
  const auto& dist = many.lights->packed().distribution;
  maps = brsm_maps(many.lights->packed(), 5000, 8);
  ASSERT_EQ(maps.size(), 8u);
  total = 0;
  uint32_t next = 0;
  for (const BrsmMap& m : maps) {
    EXPECT_EQ(m.first_light, next) << "the maps' runs are consecutive and cover every light";
    next = m.end_light;
    EXPECT_GE(m.vpl_count, 1u);
    EXPECT_NEAR(double(m.vpl_count), 5000.0 * m.pmf_sum, 2.0);
    total += m.vpl_count;
  }
  EXPECT_EQ(next, uint32_t(dist.size()));
  EXPECT_EQ(total, 5000u);
  EXPECT_EQ(brsm_maps(many.lights->packed(), 3, 8).size(), 3u) << "no more maps than VPLs";
  PreparedScene dark(test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f));
  EXPECT_TRUE(brsm_maps(dark.lights->packed(), 100, 8).empty());
}

const vec3 kAlbedo(0.7f, 0.5f, 0.3f);

Scene box_with_point_light() {
  Scene scene = test::diffuse_box(kAlbedo, 2.0f);
  scene.lights.push_back(test::punctual_light(LightType::Point, {0.2f, -0.3f, 0.1f}, {0, 0, -1}, {1.0f, 2.0f, 0.5f}));
  return scene;
}

// In a closed box every texel's ray hits a wall, and each pVPL of a point light stands for the
// same flux (4 pi I / R^2, the map being equal-area): drawn by power alone, every VPL carries the
// pVPLs' total over the VPL count, albedo 4 I per channel in all, whatever the random numbers.
TEST(BrsmFlux, DrawnByPowerEveryVplCarriesAnEqualShareOfTheReflectedFlux) {
  PreparedScene p(box_with_point_light());
  VplParams pr = brsm_params(3000, 64);
  pr.brsm_power_fraction = 1.0f;
  VplStats stats;
  VplSet vpls = generate_brsm_vpls(p.scene, *p.accel, *p.lights, pr, scene_view(p.scene, 32, 32), 3, true, &stats);
  ASSERT_EQ(vpls.size(), 3000u);
  expect_all_finite(vpls);
  EXPECT_EQ(stats.maps, 1u);
  EXPECT_EQ(stats.pvpls, 64u * 64u);
  EXPECT_EQ(stats.rays, 64u * 64u + 8u * 8u);  // texels and the 8 x 8 G-buffer (scale 0.25)
  const vec3 expected = kAlbedo * vec3(1.0f, 2.0f, 0.5f) * 4.0f;
  dvec3 sum = intensity_sum(vpls);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], expected[c], 1e-4 * expected[c]) << c;
  EXPECT_EQ(to_json(stats)["source"], "brsm");
  EXPECT_EQ(to_json(stats)["stage_ms"].size(), 5u);
}

// Drawn by weight, a set's total varies with the draws, and with a power share its expectation is
// still the pVPLs' total: tested over independent seeds with and without the filter and the
// screen-wide samples. The weights alone (power share 0) drop the pVPLs that light nothing the
// camera sees (those on the walls behind it light only walls it does not see either), so their
// total is below the pVPLs': harmless for the image, which is what the one-bounce tests below
// check, and the reason the share exists.
TEST(BrsmFlux, ExpectedFluxIsThePvplsWithAPowerShare) {
  PreparedScene p(box_with_point_light());
  const vec3 expected = kAlbedo * vec3(1.0f, 2.0f, 0.5f) * 4.0f;
  struct Variant {
    bool filter;
    int screen_samples;
    float power_fraction;
  };
  for (const Variant v : {Variant{true, 8, 0.01f}, Variant{false, 8, 0.1f}, Variant{true, 0, 0.1f}, Variant{true, 8, 0.0f}}) {
    VplParams pr = brsm_params(500, 32);
    pr.brsm_filter = v.filter;
    pr.brsm_screen_samples = v.screen_samples;
    pr.brsm_power_fraction = v.power_fraction;
    std::vector<double> sums[3];
    double spread = 0.0;
    for (uint32_t seed = 0; seed < 40; ++seed) {
      VplSet vpls = generate_brsm_vpls(p.scene, *p.accel, *p.lights, pr, scene_view(p.scene, 32, 32), seed, true);
      ASSERT_EQ(vpls.size(), 500u);
      dvec3 s = intensity_sum(vpls);
      for (int c = 0; c < 3; ++c) sums[c].push_back(s[c]);
    }
    const std::string label = "filter " + std::to_string(v.filter) + ", screen samples " +
                              std::to_string(v.screen_samples) + ", power share " + std::to_string(v.power_fraction);
    for (int c = 0; c < 3; ++c) {
      test::MeanError m = test::mean_error(sums[c]);
      if (v.power_fraction > 0.0f)
        EXPECT_NEAR(m.mean, expected[c], 5.0 * m.error) << label << ", channel " << c;
      else
        EXPECT_LT(m.mean, expected[c] - 5.0 * m.error) << label << ", channel " << c;
      spread = std::max(spread, m.error * std::sqrt(40.0) / expected[c]);
    }
    EXPECT_GT(spread, 1e-3) << "weighted draws vary the total, or this test has no power (" << label << ")";
  }
}

TEST(BrsmDeterminism, SameBitsWhateverTheThreadCount) {
  PreparedScene p(load_default_scene());
  VplParams pr = brsm_params(5000, 64);
  const auto view = scene_view(p.scene, 48, 48);
  auto run = [&](int threads, uint32_t seed) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    return generate_brsm_vpls(p.scene, *p.accel, *p.lights, pr, view, seed, false);
  };
  VplSet one = run(1, 9), two = run(2, 9), other = run(2, 10);
  ASSERT_EQ(one.size(), 5000u);
  ASSERT_EQ(two.size(), one.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(Vpl)), 0);
  ASSERT_EQ(other.size(), one.size());
  EXPECT_NE(std::memcmp(one.data(), other.data(), one.size() * sizeof(Vpl)), 0);
  expect_all_finite(one);
}

TEST(BrsmExtremes, NoLightsSmallCountsAndLightsThatMissEverything) {
  PreparedScene dark(test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f));
  VplStats stats;
  EXPECT_TRUE(generate_brsm_vpls(dark.scene, *dark.accel, *dark.lights, brsm_params(100, 16),
                                 scene_view(dark.scene, 16, 16), 1, true, &stats)
                  .empty());
  EXPECT_EQ(stats.rays, 0u);

  PreparedScene box(box_with_point_light());
  for (int n : {1, 2, 3}) {
    VplSet vpls = generate_brsm_vpls(box.scene, *box.accel, *box.lights, brsm_params(n, 2), scene_view(box.scene, 8, 8),
                                     1, true);
    EXPECT_EQ(vpls.size(), size_t(n));
    expect_all_finite(vpls);
  }
  // A spot light aimed away from a plane: every texel's ray escapes, and the set is empty.
  Scene plane = test::lambert_plane(0.5f, 1.0f, 5.0f, 1.0f);
  PunctualLight spot = test::punctual_light(LightType::Spot, {0, 0, 1}, {0, 0, 1}, vec3(10.0f));
  spot.cos_outer = 0.9f;
  spot.cos_inner = 0.95f;
  plane.lights.push_back(spot);
  PreparedScene away(std::move(plane));
  EXPECT_TRUE(generate_brsm_vpls(away.scene, *away.accel, *away.lights, brsm_params(100, 16),
                                 scene_view(away.scene, 16, 16), 1, true, &stats)
                  .empty());
  EXPECT_EQ(stats.maps, 1u);
  EXPECT_EQ(stats.pvpls, 0u);
}

TEST(BrsmParamsCheck, BadValuesNameTheParameter) {
  auto message = [](const VplParams& p) {
    try {
      validate(p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  VplParams p;
  p.vpl_source = "rsm";
  EXPECT_NE(message(p).find("vpl_source"), std::string::npos);
  p = VplParams{};
  p.brsm_resolution = 100;
  EXPECT_NE(message(p).find("brsm_resolution"), std::string::npos);
  p = VplParams{};
  p.brsm_resolution = 0;
  EXPECT_EQ(message(p), "no error") << "0: from the VPL count";
  p.brsm_texels_per_vpl = 0.0f;
  EXPECT_NE(message(p).find("brsm_texels_per_vpl"), std::string::npos);
  p = VplParams{};
  p.brsm_gbuffer_scale = 0.0f;
  EXPECT_NE(message(p).find("brsm_gbuffer_scale"), std::string::npos);
  p = VplParams{};
  p.brsm_power_fraction = 1.5f;
  EXPECT_NE(message(p).find("brsm_power_fraction"), std::string::npos);
  p = VplParams{};
  p.brsm_radius = -1.0f;
  EXPECT_NE(message(p).find("brsm_radius"), std::string::npos);
  p = VplParams{};
  p.brsm_maps = 0;
  EXPECT_NE(message(p).find("brsm_maps"), std::string::npos);
}

// brsm_resolution 0: the side follows the VPLs of the map that draws the most.
TEST(BrsmAutoResolution, GivesTheMostDrawnMapItsTexelsPerVpl) {
  auto side = [](std::vector<uint32_t> counts, float texels_per_vpl) {
    std::vector<BrsmMap> maps(counts.size());
    for (size_t i = 0; i < counts.size(); ++i) maps[i].vpl_count = counts[i];
    return brsm_auto_resolution(maps, texels_per_vpl);
  };
  EXPECT_EQ(side({4096}, 1.0f), 64u);
  EXPECT_EQ(side({4097}, 1.0f), 128u);
  EXPECT_EQ(side({4096}, 4.0f), 128u);
  EXPECT_EQ(side({1000, 50000, 3}, 1.0f), 256u) << "the largest map decides";
  EXPECT_EQ(side({100000}, 1.0f), 512u);
  EXPECT_EQ(side({100000}, 0.25f), 256u);
  EXPECT_EQ(side({1}, 1.0f), 16u) << "at least 16";
  EXPECT_EQ(side({4000000}, 16.0f), 4096u) << "at most 4096";
  EXPECT_EQ(side({}, 1.0f), 16u);

  // The plan takes it when brsm_resolution is 0 and keeps a given side; the record names it.
  PreparedScene box(box_with_point_light());
  const glsl::ViewParams view = scene_view(box.scene, 16, 16);
  VplStats stats;
  VplParams p = brsm_params(5000, 0);
  BrsmPlan plan = brsm_plan(box.scene, box.lights->packed(), p, view, 1, true, EmissionFocus{}, stats);
  EXPECT_EQ(plan.settings.resolution, 128u) << "one map of 5000 VPLs, one texel each";
  EXPECT_EQ(stats.resolution, 128u);
  p.brsm_resolution = 32;
  EXPECT_EQ(brsm_plan(box.scene, box.lights->packed(), p, view, 1, true, EmissionFocus{}, stats).settings.resolution,
            32u);
}

// ---- One-bounce light per image block ------------------------------------------------------

constexpr int kSize = 32, kBlock = 4, kSeeds = 12;

test::SeedBlockMeans indirect_blocks(const Scene& scene, const char* method, int spp, const nlohmann::json& params) {
  test::SeedBlockMeans s(kSize, kSize, kBlock);
  for (int seed = 0; seed < kSeeds; ++seed) {
    RenderOptions o = RenderOptions{};
    o.method = method;
    o.width = o.height = kSize;
    o.spp = spp;
    o.seed = uint32_t(300 + seed);
    o.diffuse_only = true;
    s.add(render_frame(scene, o, params).frame.indirect);
  }
  return s;
}

// Per 4 x 4 block and channel (192 Welch tests with about 22 degrees of freedom; |t| > 6.5 has a
// probability below 1e-5 for the whole image under the null hypothesis): slc's indirect light from
// BRSM VPLs against slc's from one-bounce path VPLs and against the one-bounce path tracer's, each
// over 12 seeds. The clamp is compensated (one bounce), so all three estimate the same light.
void expect_one_bounce_agrees(const Scene& scene, const char* name) {
  const nlohmann::json brsm = {{"vpl_source", "brsm"}, {"vpls", 2048}, {"brsm_resolution", 64}};
  const nlohmann::json paths = {{"vpls", 2048}, {"vpl_max_bounces", 1}};
  test::SeedBlockMeans b = indirect_blocks(scene, "slc", 8, brsm);
  test::SeedBlockMeans v = indirect_blocks(scene, "slc", 8, paths);
  test::SeedBlockMeans pt = indirect_blocks(scene, "pt", 32, {{"max_bounces", 1}});
  test::BlockTTest against_paths = test::block_t_test(b, v, 6.5), against_pt = test::block_t_test(b, pt, 6.5);
  std::printf("%s one-bounce indirect: brsm %.5f, paths %.5f, pt %.5f; largest |t| %.2f (paths), %.2f (pt); "
              "summed variance of the block means brsm %.3e, paths %.3e\n",
              name, b.image_mean(), v.image_mean(), pt.image_mean(), against_paths.largest, against_pt.largest,
              b.summed_variance(), v.summed_variance());
  EXPECT_EQ(against_paths.failures, 0) << name;
  EXPECT_EQ(against_pt.failures, 0) << name;
  EXPECT_GT(b.image_mean(), 0.0) << "no indirect light, or this test has no power";
}

TEST(BrsmOneBounce, EqualsPathVplsAndThePathTracerOnTheCornellBox) {
  expect_one_bounce_agrees(load_default_scene(), "Cornell box");
}

TEST(BrsmOneBounce, EqualsPathVplsAndThePathTracerOnTheBreakfastRoom) {
  std::filesystem::path path = test::shared_scene("breakfast-room/breakfast-room.gltf");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "no shared scenes at " << path;
  expect_one_bounce_agrees(load_gltf(path.string()), "breakfast room");
}

}  // namespace
}  // namespace sst
