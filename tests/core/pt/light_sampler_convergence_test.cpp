// `pt` converges to the same image whichever light sampler picks its lights (issue 13's
// unbiasedness): per 4x4-pixel block and channel, the mean over independent seeds with each
// sampler against the power sampler's, a two-sample t-test with the variances measured over the
// seeds, at a threshold Bonferroni-corrected for the number of blocks; and the image means.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/pipeline/renderer.h"
#include "tests/analytic_scenes.h"

namespace sst {
namespace {

constexpr int kSize = 32, kBlock = 4, kSeeds = 12;

// Per block and channel: the mean over seeds of the block's mean, and the variance of that mean.
struct BlockStats {
  std::vector<double> mean, variance_of_mean;
};

BlockStats render_blocks(const Scene& scene, const char* sampler, int max_bounces, int spp) {
  const int blocks = (kSize / kBlock) * (kSize / kBlock) * 3;
  std::vector<double> sum(blocks, 0.0), sum2(blocks, 0.0);
  for (int seed = 0; seed < kSeeds; ++seed) {
    RenderOptions o;
    o.method = "pt";
    o.width = o.height = kSize;
    o.spp = spp;
    o.seed = uint32_t(100 + seed);
    o.diffuse_only = true;
    o.light_sampler = sampler;
    RenderResult r = render_frame(scene, o, {{"max_bounces", max_bounces}});
    std::vector<double> block(blocks, 0.0);
    const Image& img = r.frame.color;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        for (int c = 0; c < 3; ++c)
          block[((y / kBlock) * (kSize / kBlock) + x / kBlock) * 3 + c] +=
              img.data[(size_t(y) * kSize + x) * img.channels + c] / double(kBlock * kBlock);
    for (int b = 0; b < blocks; ++b) sum[b] += block[b], sum2[b] += block[b] * block[b];
  }
  BlockStats s;
  for (int b = 0; b < blocks; ++b) {
    double m = sum[b] / kSeeds;
    s.mean.push_back(m);
    s.variance_of_mean.push_back(std::max(0.0, (sum2[b] / kSeeds - m * m) * kSeeds / (kSeeds - 1)) / kSeeds);
  }
  return s;
}

// Welch's t of every block against the power sampler's; 192 tests with 22 degrees of freedom:
// |t| > 6.5 has a probability below 1e-5 for the whole image under the null hypothesis.
void expect_same_image(const Scene& scene, int max_bounces, int spp) {
  BlockStats power = render_blocks(scene, "power", max_bounces, spp);
  double power_mean = 0.0;
  for (double m : power.mean) power_mean += m / double(power.mean.size());
  for (const char* sampler : {"uniform", "tree", "slc"}) {
    BlockStats s = render_blocks(scene, sampler, max_bounces, spp);
    int failures = 0;
    double largest = 0.0, mean = 0.0, var_power = 0.0, var = 0.0;
    for (size_t b = 0; b < s.mean.size(); ++b) {
      double sd = std::sqrt(s.variance_of_mean[b] + power.variance_of_mean[b]);
      double t = sd > 0.0 ? (s.mean[b] - power.mean[b]) / sd : 0.0;
      largest = std::max(largest, std::abs(t));
      failures += std::abs(t) > 6.5;
      mean += s.mean[b] / double(s.mean.size());
      var_power += power.variance_of_mean[b];
      var += s.variance_of_mean[b];
    }
    std::printf("%s, %d bounces: %s vs power: largest |t| %.2f over %zu blocks; image mean %.5f vs %.5f; summed "
                "variance of the block means %.3e vs %.3e (power)\n",
                scene.source.c_str(), max_bounces, sampler, largest, s.mean.size(), mean, power_mean, var, var_power);
    EXPECT_EQ(failures, 0) << sampler;
  }
}

TEST(LightSamplerConvergence, DirectLightOfManyLightsIsTheSameWithEverySampler) {
  expect_same_image(test::many_lights(31, 800, 5, 5, true), 0, 16);
}

TEST(LightSamplerConvergence, TwoBouncesOfManyLightsAreTheSameWithEverySampler) {
  expect_same_image(test::many_lights(32, 800, 5, 5, true), 2, 8);
}

}  // namespace
}  // namespace sst
