// `pt` converges to the same image whichever light sampler picks its lights (issue 13's
// unbiasedness): per 4x4-pixel block and channel, the mean over independent seeds with each
// sampler against the power sampler's, a two-sample t-test with the variances measured over the
// seeds, at a threshold Bonferroni-corrected for the number of blocks; and the image means.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/pipeline/renderer.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/scene_search.h"
#include "core/util/error.h"
#include "tests/test_util.h"
#include "tests/analytic_scenes.h"
#include "tests/stat_util.h"

namespace sst {
namespace {

constexpr int kSize = 32, kBlock = 4, kSeeds = 12;

// `sampler`: a light sampler's name, or sampler:tree build:tree distance (e.g. tree:morton:box).
test::SeedBlockMeans render_blocks(const Scene& scene, const std::string& sampler, int max_bounces, int spp) {
  test::SeedBlockMeans s(kSize, kSize, kBlock);
  for (int seed = 0; seed < kSeeds; ++seed) {
    RenderOptions o;
    o.method = "pt";
    o.width = o.height = kSize;
    o.spp = spp;
    o.seed = uint32_t(100 + seed);
    o.diffuse_only = true;
    std::string rest = sampler;
    auto take = [&rest] {
      const size_t colon = rest.find(':');
      std::string part = rest.substr(0, colon);
      rest = colon == std::string::npos ? "" : rest.substr(colon + 1);
      return part;
    };
    o.light_sampler = take();
    if (!rest.empty()) o.light_tree = take();
    if (!rest.empty()) o.light_tree_distance = take();
    s.add(render_frame(scene, o, {{"max_bounces", max_bounces}}).frame.color);
  }
  return s;
}

// Welch's t of every block against the power sampler's; 192 tests with 22 degrees of freedom:
// |t| > 6.5 has a probability below 1e-5 for the whole image under the null hypothesis.
void expect_same_image(const Scene& scene, int max_bounces, int spp,
                       std::initializer_list<const char*> samplers = {"uniform", "tree", "slc"}) {
  test::SeedBlockMeans power = render_blocks(scene, "power", max_bounces, spp);
  for (const char* sampler : samplers) {
    test::SeedBlockMeans s = render_blocks(scene, sampler, max_bounces, spp);
    test::BlockTTest t = test::block_t_test(s, power, 6.5);
    std::printf("%s, %d bounces: %s vs power: largest |t| %.2f over %d blocks; image mean %.5f vs %.5f; summed "
                "variance of the block means %.3e vs %.3e (power)\n",
                scene.source.c_str(), max_bounces, sampler, t.largest, s.size(), s.image_mean(), power.image_mean(),
                s.summed_variance(), power.summed_variance());
    EXPECT_EQ(t.failures, 0) << sampler;
  }
}

TEST(LightSamplerConvergence, DirectLightOfManyLightsIsTheSameWithEverySampler) {
  expect_same_image(test::many_lights(31, 800, 5, 5, true), 0, 16,
                    {"uniform", "tree", "slc", "tree:morton:box", "tree:saoh:mixed", "slc:morton"});
}

// The wide field of two-sided quads and punctual lights (test::light_field) with both tree builds
// and every distance rule.
TEST(LightSamplerConvergence, DirectLightOfALightFieldIsTheSameWithEveryTree) {
  expect_same_image(test::light_field(33, 600, 10, 5), 0, 16,
                    {"tree", "slc", "tree:morton:centre", "tree:saoh:box", "tree:morton:box", "tree:saoh:mixed"});
}

TEST(LightSamplerConvergence, TwoBouncesOfManyLightsAreTheSameWithEverySampler) {
  expect_same_image(test::many_lights(32, 800, 5, 5, true), 2, 8);
}

// The scenes: the shared ones (skipped where ../shared/scenes is absent) and the generated
// many-light ones (scenes/tools/make_many_lights.py; run where they are on SST_SCENE_PATH). Not
// `uniform`: on the night street its estimates are so heavy-tailed (a few bright lamps among
// thousands of dim emitters) that 12 seeds underestimate a block's variance and Welch's t
// reaches 18 while the image means agree to 0.5%.
TEST(LightSamplerConvergence, DirectLightOfRealScenesIsTheSameWithEverySampler) {
  std::vector<std::string> paths;
  for (const char* name : {"cornell-box", "breakfast-room", "staircase"}) {
    auto path = test::shared_scene(std::string(name) + "/" + name + ".gltf");
    if (!path.empty()) paths.push_back(path.string());
  }
  for (const char* name : {"cornell-lamp", "night-street", "fairground"}) {
    try {
      paths.push_back(resolve_scene(name, {}));
    } catch (const Error&) {
      std::printf("%s: not on SST_SCENE_PATH, skipped\n", name);
    }
  }
  if (paths.empty()) GTEST_SKIP() << "no shared or generated scene found";
  for (const std::string& path : paths) expect_same_image(load_gltf(path), 0, 16, {"tree", "slc"});
}

}  // namespace
}  // namespace sst
