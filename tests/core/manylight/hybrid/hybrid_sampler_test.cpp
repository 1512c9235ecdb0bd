// hybrid: expected-contribution weights, finite images at the extremes, parameter errors, the
// mean image close to exhaustive (the method is biased by design, so only loosely), and the
// nodes visited per traversal against rtslc.
#include "core/manylight/hybrid/hybrid_sampler.h"

#include <gtest/gtest.h>

#include "core/pipeline/method_registry.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "tests/core/manylight/many_light_test_util.h"

namespace sst {
namespace {

double mean(const Image& im) {
  double s = 0.0;
  for (float v : im.data) s += v;
  return im.data.empty() ? 0.0 : s / double(im.data.size());
}

TEST(HybridSampler, WeightIsZeroBehindAndFallsOffWithDistance) {
  LightNode a{};
  a.bounds_lo = vec3(1, 0, 0), a.bounds_hi = vec3(2, 1, 1), a.intensity = vec3(1), a.vpl_count = 1;
  vec3 x(0, 0.5f, 0.5f);
  EXPECT_EQ(hybrid_weight(a, x, vec3(-1, 0, 0), 0.01f, 0.0f), 0.0f);
  float near = hybrid_weight(a, x, vec3(1, 0, 0), 0.01f, 0.0f);
  float far = hybrid_weight(a, x - vec3(3, 0, 0), vec3(1, 0, 0), 0.01f, 0.0f);
  EXPECT_GT(near, far);
  EXPECT_GT(far, 0.0f);
  LightNode empty{};
  empty.bounds_lo = vec3(kInf), empty.bounds_hi = vec3(-kInf);
  EXPECT_EQ(hybrid_weight(empty, x, vec3(1, 0, 0), 0.01f, 0.0f), 0.0f);
}

TEST(HybridSampler, ExtremesGiveFiniteImages) {
  Scene scene = load_default_scene();
  std::vector<nlohmann::json> cases = {
      {{"v_min", 0.0}},     {{"v_min", 1.0}},      {{"vpls", 1}},      {{"vpls", 2}},
      {{"vpls", 3}},        {{"cut_size", 1}},     {{"cut_size", 32}}, {{"block_size", 1}},
      {{"block_size", 1000}}, {{"n_min", 1.0}},    {{"n_min", -1.0}, {"d_max", 10.0}},
  };
  for (nlohmann::json p : cases) {
    if (!p.contains("vpls")) p["vpls"] = 200;
    RenderResult r = render_frame(scene, test::small_options("hybrid", 2, 12), p);
    for (float v : r.frame.color.data) ASSERT_TRUE(std::isfinite(v)) << p.dump();
    EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u) << p.dump();
  }
}

TEST(HybridSampler, BadParametersNameTheParameter) {
  auto message = [](const nlohmann::json& p) {
    try {
      create_method("hybrid", p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"tree", "radix"}}).find("tree"), std::string::npos);
  EXPECT_NE(message({{"cut_size", 33}}).find("cut_size"), std::string::npos);
  EXPECT_NE(message({{"block_size", 0}}).find("block_size"), std::string::npos);
  EXPECT_NE(message({{"n_min", 2.0}}).find("n_min"), std::string::npos);
  EXPECT_NE(message({{"d_max", 0.0}}).find("d_max"), std::string::npos);
}

TEST(HybridSampler, MeanImageCloseToExhaustive) {
  // Biased by design (cut blending, substitutes): only the image mean is checked, loosely.
  Scene scene = load_default_scene();
  nlohmann::json vpl = {{"vpls", 400}};
  double e = mean(test::frame_layer(render_frame(scene, test::small_options("exhaustive", 16, 24), vpl), "indirect"));
  for (float v_min : {0.7f, 1.0f}) {
    nlohmann::json p = vpl;
    p["v_min"] = v_min;
    double h = mean(test::frame_layer(render_frame(scene, test::small_options("hybrid", 64, 24), p), "indirect"));
    EXPECT_NEAR(h, e, 0.15 * e) << "v_min " << v_min;
  }
}

TEST(HybridSampler, VisitsFewerNodesPerTraversalThanRtslc) {
  // The hybrid thesis, Fig. 7.2: shallow cuts plus substitutes stop earlier than RTSLC's
  // cut-to-leaf walks. Both do cut_size = 8 traversals per sample, 8x8 blocks, 4096 VPLs.
  Scene scene = load_default_scene();
  nlohmann::json p = {{"vpls", 4096}, {"block_size", 8}, {"cut_size", 8}};
  RenderResult h = render_frame(scene, test::small_options("hybrid", 4, 64), p);
  RenderResult r = render_frame(scene, test::small_options("rtslc", 4, 64), p);
  double hn = h.frame.method_counters["nodes_visited_mean"].get<double>();
  double rn = r.frame.method_counters["nodes_visited_mean"].get<double>();
  std::printf("nodes visited per sample (8 traversals): hybrid %.2f, rtslc %.2f; per traversal %.2f vs %.2f\n", hn,
              rn, hn / 8.0, rn / 8.0);
  EXPECT_LT(hn, rn);
}

}  // namespace
}  // namespace sst
