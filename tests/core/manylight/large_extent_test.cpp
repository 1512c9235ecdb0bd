// Lengths that must not come from the scene's extent (docs/design/lengths.md), and the VPL clamp's
// compensation, tested on whole renders with the seeds as samples: every seed draws another VPL
// set, whose offset all pixels share, so image means over seeds are the independent samples.
//
// scenes/window-room-10m.gltf and -10km.gltf (scenes/tools/make_window_room.py) hold the same
// sunlit room and the same 20 m of grey ground; the 10 km one adds black ground out to 5 km and
// black hills, so its light is the same while its bounding box is 500 times wider.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/lighttree/light_tree.h"
#include "core/pipeline/method_registry.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "tests/core/manylight/many_light_test_util.h"

namespace sst {
namespace {

struct SeedMeans {
  double mean = 0.0, variance = 0.0;  // over seeds, of the image mean of one layer
  int n = 0;
};

double image_mean(const Image& image) {
  double sum = 0.0;
  for (float v : image.data) sum += double(v);
  return sum / double(image.data.size());
}

SeedMeans seed_means(const Scene& scene, RenderOptions options, const nlohmann::json& params, int seeds,
                     const std::string& layer) {
  std::vector<double> m;
  for (int s = 0; s < seeds; ++s) {
    options.seed = uint32_t(100 + s);
    RenderResult r = render_frame(scene, options, params);
    EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u);
    m.push_back(image_mean(layer == "color" ? r.frame.color : test::frame_layer(r, layer)));
  }
  SeedMeans out;
  out.n = seeds;
  for (double v : m) out.mean += v / seeds;
  for (double v : m) out.variance += (v - out.mean) * (v - out.mean) / (seeds - 1);
  return out;
}

// Welch's t of the difference of two means.
double welch_t(const SeedMeans& a, const SeedMeans& b) {
  return (a.mean - b.mean) / std::sqrt(a.variance / a.n + b.variance / b.n);
}

Scene window_room(const char* name) {
  return load_gltf(std::string(SST_SOURCE_DIR) + "/scenes/" + name);
}

RenderOptions room_options(const char* method) {
  RenderOptions o = test::small_options(method, 2, 32);
  o.height = 18;
  return o;
}

// With 8 seeds a side, |t| above 5 has a probability below 1e-3 for equal means (Welch, ~14
// degrees of freedom), so this fails on a real difference, never on the noise of fixed seeds.
constexpr double kMaxT = 5.0;
constexpr int kSeeds = 8;

class LargeExtent : public ::testing::TestWithParam<std::string> {};

// Growing the black far geometry from 10 m to 10 km changes no light, so no method's image mean
// may move by more than its seed-to-seed noise.
TEST_P(LargeExtent, ImageMeanIgnoresFarGeometry) {
  const nlohmann::json params = {{"vpls", 20000}};
  SeedMeans near = seed_means(window_room("window-room-10m.gltf"), room_options(GetParam().c_str()), params, kSeeds,
                              "color");
  SeedMeans far = seed_means(window_room("window-room-10km.gltf"), room_options(GetParam().c_str()), params, kSeeds,
                             "color");
  double t = welch_t(far, near);
  EXPECT_LT(std::abs(t), kMaxT) << GetParam() << ": 10 m " << near.mean << ", 10 km " << far.mean;
  std::printf("%-8s 10 m %.5f +- %.5f, 10 km %.5f +- %.5f, t %.2f\n", GetParam().c_str(), near.mean,
              std::sqrt(near.variance / near.n), far.mean, std::sqrt(far.variance / far.n), t);
}

INSTANTIATE_TEST_SUITE_P(VplMethods, LargeExtent, ::testing::Values("slc", "sst", "rtslc", "hybrid"),
                         [](const auto& info) { return info.param; });

class NodeDistanceFloor : public ::testing::TestWithParam<std::string> {};

// The floor changes which VPLs a walk favours, never which it can reach: every method's per-pixel
// means with it equal the exhaustive sum over the same VPLs (few VPLs, many samples, as the
// methods' own unbiasedness tests; 4096 spp for rtslc's skewed pixels, see RtslcSampler). sst and
// the hybrid without what biases them by design: substitutes (the hybrid's stand in only where a
// box is a millionth of its distance wide: nowhere) and the hybrid's blending of the cuts of
// neighbouring blocks (one block).
TEST_P(NodeDistanceFloor, KeepsEveryWalkUnbiased) {
  Scene scene = load_default_scene();
  nlohmann::json p = {{"vpls", 24}, {"vpl_max_bounces", 3}};
  RenderResult exhaustive = render_frame(scene, test::small_options("exhaustive", 4096, 16), p);
  if (GetParam() == "sst") p["substitutes"] = false;
  if (GetParam() == "hybrid") {
    p["block_size"] = 1000;
    p["substitute_max_extent"] = 1e-6;
  }
  p["node_distance_floor"] = 0.5;
  p["node_distance_floor_above"] = 0.0;  // the Cornell box's VPLs span under every threshold
  RenderResult r = render_frame(scene, test::small_options(GetParam().c_str(), 4096, 16), p);
  EXPECT_EQ(r.frame.method_counters["tree"]["node_distance_floor"], 0.5);
  EXPECT_EQ(test::z_test_failures(test::frame_layer(r, "indirect"), test::frame_layer(r, "indirect_variance"),
                                  test::frame_layer(exhaustive, "indirect"), 5.1),
            0);
  EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u);
  p["node_distance_floor"] = 0.0;
  RenderResult yuksel = render_frame(scene, test::small_options(GetParam().c_str(), 4096, 16), p);
  EXPECT_NE(yuksel.frame.color.data, r.frame.color.data) << "the floor changed nothing";
}

// The floor acts where the VPLs' box is wider than node_distance_floor_above view lengths, as in
// a landscape around the view, and not in a room (the default scene: the papers' rules, bits
// and all). The threshold is each method's: 2.5 view lengths for slc, 2 for sst, 50 for the cut
// methods (TreeMethodParams).
TEST(NodeDistanceFloor, ActsOnlyWhereTheVplsSpanManyViewLengths) {
  for (auto [method, above] : {std::pair{"slc", 2.5}, {"sst", 2.0}, {"rtslc", 50.0}, {"hybrid", 50.0}})
    EXPECT_EQ(create_method(method, {})->params()["node_distance_floor_above"], above) << method;
  LightTreeParams params;  // floor 0.1 above 50 view lengths
  const Bounds3 km{vec3(-500.0f, 0.0f, -500.0f), vec3(500.0f, 10.0f, 500.0f)};
  EXPECT_EQ(node_distance_floor_for(params, km, 10.0f), 0.1f);
  EXPECT_EQ(node_distance_floor_for(params, km, 100.0f), 0.0f);
  EXPECT_EQ(node_distance_floor_for(params, Bounds3{}, 0.0f), 0.0f);
  params.node_distance_floor_above = 0.0f;
  EXPECT_EQ(node_distance_floor_for(params, km, 100.0f), 0.1f);

  Scene scene = load_default_scene();
  const nlohmann::json vpl = {{"vpls", 200}};
  RenderResult defaults = render_frame(scene, test::small_options("slc", 2, 8), vpl);
  EXPECT_EQ(defaults.frame.method_counters["tree"]["node_distance_floor"], 0.0);
  RenderResult papers = render_frame(scene, test::small_options("slc", 2, 8), {{"vpls", 200}, {"node_distance_floor", 0.0}});
  EXPECT_EQ(defaults.frame.color.data, papers.frame.color.data);
  // The record gives the extent the threshold is compared with; the floor acts just above it.
  const double lengths = defaults.frame.method_counters["tree"]["vpl_view_lengths"].get<double>();
  EXPECT_GT(lengths, 0.1);
  EXPECT_LT(lengths, 2.0) << "the Cornell box's VPLs span less than every threshold";
  for (auto [above, floor] : {std::pair{0.99 * lengths, 0.1}, {1.01 * lengths, 0.0}}) {
    RenderResult r = render_frame(scene, test::small_options("slc", 2, 8), {{"vpls", 200}, {"node_distance_floor_above", above}});
    EXPECT_NEAR(r.frame.method_counters["tree"]["node_distance_floor"].get<double>(), floor, 1e-6) << above;
  }
}

INSTANTIATE_TEST_SUITE_P(VplMethods, NodeDistanceFloor, ::testing::Values("slc", "sst", "rtslc", "hybrid"),
                         [](const auto& info) { return info.param; });

// The scenes do show the disease: with the clamp relative to the VPLs' bounds, no compensation and
// the sun's paths spread over the whole scene (sst before these lengths were made local), the room
// of the 10 km scene loses most of its indirect light.
TEST(LargeExtentScenes, TheOldLengthsDarkenTheFarScene) {
  const nlohmann::json old = {{"vpls", 20000},
                              {"clamp_relative_to", "vpl_bounds"},
                              {"clamp_fraction", 0.01},
                              {"clamp_compensation", false},
                              {"directional_focus", 0.0}};
  SeedMeans near = seed_means(window_room("window-room-10m.gltf"), room_options("slc"), old, 4, "indirect");
  SeedMeans far = seed_means(window_room("window-room-10km.gltf"), room_options("slc"), old, 4, "indirect");
  EXPECT_LT(far.mean, 0.5 * near.mean);
}

// Kollig and Keller's compensation: slc's clamped estimate plus the compensating paths converges
// to the path tracer's indirect light, while the clamp alone darkens it, on the Cornell box with a
// clamp of 0.3 of the camera distance (about 1.2 m in a 2 m box: most indirect light is near).
TEST(ClampCompensation, CompensatedClampConvergesToThePathTracer) {
  Scene scene = load_default_scene();
  // The path tracer's mean over 4 seeds of 1024 spp (one such mean is off by up to ~0.6%).
  SeedMeans pt = seed_means(scene, test::small_options("pt", 1024, 24), {{"max_bounces", 8}}, 4, "indirect");
  const nlohmann::json base = {{"vpls", 4096}, {"clamp_fraction", 0.3}};
  nlohmann::json clamped = base;
  clamped["clamp_compensation"] = false;
  SeedMeans compensated = seed_means(scene, test::small_options("slc", 16, 24), base, kSeeds, "indirect");
  SeedMeans plain = seed_means(scene, test::small_options("slc", 16, 24), clamped, kSeeds, "indirect");
  double t_comp = welch_t(compensated, pt), t_plain = welch_t(plain, pt);
  std::printf("pt %.5f, compensated %.5f (t %.2f), clamped %.5f (t %.2f)\n", pt.mean, compensated.mean, t_comp,
              plain.mean, t_plain);
  EXPECT_LT(std::abs(t_comp), kMaxT);
  EXPECT_LT(t_plain, -kMaxT) << "the clamp alone must be measurably dark here, or this test has no power";
}

}  // namespace
}  // namespace sst
