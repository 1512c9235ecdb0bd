// rtslc with direct_light = cuts, RTSLC's per-block cuts on the scene's own emitters: every cut of
// the emitter tree holds every light exactly once; the direct layer converges to the path
// tracer's direct light (Welch t per block over seeds); the parameters and the light sampler it
// needs are checked with errors that name them.
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <random>

#include "core/lights/light_sampler.h"
#include "core/pipeline/method_registry.h"
#include "core/pipeline/renderer.h"
#include "tests/analytic_scenes.h"
#include "tests/core/manylight/many_light_test_util.h"
#include "tests/stat_util.h"

namespace sst {
namespace {

// How often each distribution entry lies below a node of `cut`.
std::vector<int> coverage(const PackedLights& lights, const std::vector<uint32_t>& cut) {
  std::vector<int> count(lights.distribution.size(), 0);
  std::vector<uint32_t> stack(cut.begin(), cut.end());
  while (!stack.empty()) {
    const EmitterNode& node = lights.tree[stack.back()];
    stack.pop_back();
    if (node.children != 0u) {
      stack.push_back(node.children);
      stack.push_back(node.children + 1);
    } else if (node.entry != LIGHT_NONE) {  // a leaf, or a directional light beside the tree
      ++count[node.entry];
    }
  }
  return count;
}

TEST(RtslcDirect, EveryCutOfTheEmitterTreeHoldsEveryLightOnce) {
  Scene scene = test::many_lights(5, 300, 4, 4, true);
  LightSampler sampler(scene, LightSamplerKind::Tree);
  const PackedLights& lights = sampler.packed();
  const uint32_t leaves = lights.header.tree_leaves, directional = lights.header.directional_count;
  ASSERT_EQ(directional, 1u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int trials = 0;
  for (uint32_t max_nodes : {1u, 2u, 8u, 32u, 100u}) {
    for (int i = 0; i < 50; ++i, ++trials) {
      vec3 p = vec3(4.0f * u(rng), 2.0f + 2.0f * u(rng), 4.0f * u(rng));
      vec3 n = glm::normalize(vec3(u(rng), u(rng), u(rng)) + vec3(0.0f, 0.1f, 0.0f));
      std::vector<uint32_t> cut;
      emitter_tree_cut(lights.tree, leaves, directional, lights.header.tree_distance, i % 10 != 0, p, n, max_nodes, cut);
      // The root and the sun always; beyond that, splits until max_nodes.
      EXPECT_LE(cut.size(), std::max<size_t>(max_nodes, 2)) << max_nodes;
      EXPECT_GE(cut.size(), std::min<size_t>(max_nodes, 2)) << max_nodes;
      std::vector<int> count = coverage(lights, cut);
      for (size_t e = 0; e < count.size(); ++e)
        ASSERT_EQ(count[e], lights.distribution[e].tree_node == LIGHT_NONE ? 0 : 1)
            << "entry " << e << ", max_nodes " << max_nodes;
    }
  }
  EXPECT_EQ(trials, 250);
}

constexpr int kSize = 32, kBlock = 4, kSeeds = 12;

test::SeedBlockMeans direct_blocks(const Scene& scene, const std::string& method, const std::string& sampler,
                                   const nlohmann::json& params, int spp) {
  test::SeedBlockMeans s(kSize, kSize, kBlock);
  for (int seed = 0; seed < kSeeds; ++seed) {
    RenderOptions o;
    o.method = method;
    o.width = o.height = kSize;
    o.spp = spp;
    o.seed = uint32_t(200 + seed);
    o.diffuse_only = true;
    o.light_sampler = sampler;
    s.add(render_frame(scene, o, params).frame.direct);
  }
  return s;
}

// Per 4x4 block and channel, rtslc's direct layer against pt's (max_bounces 0, power sampler):
// 192 Welch tests with 22 degrees of freedom, |t| > 6.5 has a probability below 1e-5 for the
// whole image under the null hypothesis. Interleaving is unbiased over each 2x2 tile, which the
// 4x4 blocks hold whole.
TEST(RtslcDirect, DirectLightFromCutsConvergesToThePathTracers) {
  Scene scene = test::many_lights(31, 800, 5, 5, true);
  test::SeedBlockMeans pt = direct_blocks(scene, "pt", "power", {{"max_bounces", 0}}, 16);
  struct Variant {
    const char* sampler;
    nlohmann::json params;
  };
  const Variant variants[] = {
      {"tree", {{"direct_light", "cuts"}}},
      {"slc", {{"direct_light", "cuts"}, {"direct_cut_size", 3}}},
      {"tree", {{"direct_light", "cuts"}, {"interleave", 2}, {"block_size", 4}}},
  };
  for (const Variant& v : variants) {
    nlohmann::json params = v.params;
    params["vpls"] = 64;
    test::SeedBlockMeans r = direct_blocks(scene, "rtslc", v.sampler, params, 16);
    test::BlockTTest t = test::block_t_test(r, pt, 6.5);
    std::printf("rtslc %s %s vs pt (power): largest |t| %.2f over %d blocks; image mean %.5f vs %.5f; summed "
                "variance of the block means %.3e vs %.3e (pt)\n",
                v.sampler, params.dump().c_str(), t.largest, r.size(), r.image_mean(), pt.image_mean(),
                r.summed_variance(), pt.summed_variance());
    EXPECT_EQ(t.failures, 0) << v.sampler << " " << params.dump();
  }
}

TEST(RtslcDirect, CutsNeedTheEmitterTreeAndValidParameters) {
  Scene scene = test::many_lights(5, 50, 1, 1, false);
  RenderOptions o;
  o.method = "rtslc";
  o.width = o.height = 8;
  o.light_sampler = "power";
  try {
    render_frame(scene, o, {{"vpls", 16}, {"direct_light", "cuts"}});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--light-sampler tree or slc"), std::string::npos) << e.what();
  }
  auto message = [](const nlohmann::json& p) { return test::create_method_error("rtslc", p); };
  EXPECT_NE(message({{"direct_light", "tree"}}).find("'direct_light'"), std::string::npos);
  EXPECT_NE(message({{"direct_cut_size", 0}}).find("direct_cut_size"), std::string::npos);
  EXPECT_NE(message({{"direct_cut_size", 33}}).find("direct_cut_size"), std::string::npos);
  EXPECT_EQ(message({{"direct_light", "cuts"}, {"direct_cut_size", 32}}), "no error");
}

}  // namespace
}  // namespace sst
