// gi10 on lavapipe against the CPU (issue 12, acceptance 5). One frame without history is the same
// arithmetic on both backends: the images agree to the last bits (measured: 2e-8 relative RMSE;
// the driver may fuse a * b + c where the shared code has no `precise`). After warm-up they agree
// only statistically: every frame's guiding picks a probe ray's texel by comparing reconstructed
// luminances with a random threshold, so a difference in the last bit of one texel sends a ray
// elsewhere, and the two backends' caches then hold different samples of the same distribution
// (measured after 24 frames: 2.6% relative RMSE, means within 0.13%).
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cmath>

#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "tests/gpu/gpu_test_util.h"

namespace sst {
namespace {

RenderResult render_on(const std::string& backend, const nlohmann::json& params) {
  RenderOptions o;
  o.method = "gi10";
  o.backend = backend;
  o.accel = "flat";  // the GPU's BVH on the CPU too: the same hits
  o.width = 96;
  o.height = 72;
  o.spp = 1;
  o.diffuse_only = true;
  return render_frame(load_default_scene(), o, params);
}

const Image& layer(const RenderResult& r, const std::string& name) {
  for (const Layer& l : r.frame.extra_layers)
    if (l.name == name) return l.image;
  throw Error("no layer " + name);
}

double mean(const Image& img) { return test::image_mean(img); }

TEST(Gi10Vulkan, TheFirstFrameEqualsTheCpus) {
  if (std::string why = test::gpu_unavailable("gi10_0"); !why.empty()) GTEST_SKIP() << why;
  nlohmann::json p = {{"cache_warmup_frames", 0}};
  RenderResult gpu = render_on("vulkan", p), cpu = render_on("cpu", p);
  double raw = test::relative_rmse(layer(gpu, "gi10_irradiance_raw"), layer(cpu, "gi10_irradiance_raw"));
  double color = test::relative_rmse(gpu.frame.color, cpu.frame.color);
  std::printf("frame 0: relative RMSE raw irradiance %.3g, image %.3g\n", raw, color);
  EXPECT_LT(raw, 1e-3);
  EXPECT_LT(color, 1e-3);
  EXPECT_EQ(gpu.frame.method_counters["probe_hits"], cpu.frame.method_counters["probe_hits"]);
  EXPECT_EQ(gpu.frame.method_counters["live_tiles"], cpu.frame.method_counters["live_tiles"]);
}

TEST(Gi10Vulkan, AfterWarmUpAgreesWithTheCpuInDistribution) {
  if (std::string why = test::gpu_unavailable("gi10_0"); !why.empty()) GTEST_SKIP() << why;
  nlohmann::json p = {{"cache_warmup_frames", 24}};
  RenderResult gpu = render_on("vulkan", p), cpu = render_on("cpu", p);
  const Image &g = layer(gpu, "gi10_irradiance"), &c = layer(cpu, "gi10_irradiance");
  double rel = test::relative_rmse(g, c);
  double m = mean(g) / mean(c);
  std::printf("after 24 frames: relative RMSE %.3g, mean ratio %.5f\n", rel, m);
  EXPECT_NEAR(m, 1.0, 0.01);
  EXPECT_LT(rel, 0.06);
}

}  // namespace
}  // namespace sst

#endif  // SST_HAVE_VULKAN
