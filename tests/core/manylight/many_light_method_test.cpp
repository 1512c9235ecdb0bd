// The VPL pipeline: exhaustive VPL shading against the path tracer, and the uniform sampler's
// convergence to exhaustive on the same VPL set (per-pixel z-test with the variance image).
#include <gtest/gtest.h>

#include "core/render/renderer.h"
#include "core/scene/default_scene.h"
#include "tests/analytic_scenes.h"

namespace sst {
namespace {

RenderOptions small(const char* method, int spp, int width = 24) {
  RenderOptions o;
  o.method = method;
  o.width = o.height = width;
  o.spp = spp;
  o.diffuse_only = true;
  o.seed = 3;
  return o;
}

Image layer(const RenderResult& r, const std::string& name) {
  for (const Layer& l : r.frame.layers())
    if (l.name == name) return l.image;
  ADD_FAILURE() << "no layer " << name;
  return {};
}

// Per-pixel z-test of `test` (with its variance of the mean) against a noiseless `expected`,
// Bonferroni-corrected for the number of pixel-channels at family-wise level 1e-4 (|z| < 5.1
// for 3k pixel-channels). Returns the number of failures.
int z_test_failures(const Image& test, const Image& variance, const Image& expected, double z_max) {
  int failures = 0;
  for (size_t i = 0; i < test.data.size(); ++i) {
    double diff = double(test.data[i]) - double(expected.data[i]);
    double sd = std::sqrt(double(variance.data[i]));
    if (sd == 0.0 ? std::abs(diff) > 1e-6 * (1.0 + std::abs(expected.data[i])) : std::abs(diff) / sd > z_max) ++failures;
  }
  return failures;
}

TEST(ManyLightMethod, UniformConvergesToExhaustiveOnTheSameVpls) {
  // Few VPLs and many samples: every VPL is drawn ~40 times per pixel, so the pixel means are
  // close to normal and the sample variance is a fair estimate (with hundreds of VPLs a nearby
  // one, drawn a couple of times, makes the per-pixel distribution too skewed for a z-test).
  Scene scene = load_default_scene();
  nlohmann::json vpl = {{"vpls", 24}, {"vpl_max_bounces", 3}};
  // Same seed and spp: both renders jitter their camera rays identically, so the exhaustive
  // image is exactly the expectation of the uniform one, pixel by pixel.
  RenderResult uniform = render_frame(scene, small("uniform", 1024, 16), vpl);
  RenderResult exhaustive = render_frame(scene, small("exhaustive", 1024, 16), vpl);
  Image u = layer(uniform, "indirect"), var = layer(uniform, "indirect_variance");
  Image e = layer(exhaustive, "indirect");
  EXPECT_EQ(z_test_failures(u, var, e, 5.1), 0);
  EXPECT_EQ(uniform.frame.counters.nonfinite_samples, 0u);
}

TEST(ManyLightMethod, RecordsVplStatsAndLayers) {
  RenderResult r = render_frame(load_default_scene(), small("uniform", 2, 16), {{"vpls", 100}});
  EXPECT_EQ(r.frame.method_counters["vpl"]["vpls"], 100);
  EXPECT_GT(r.timer.ms("vpl_generation"), 0.0);
  EXPECT_GT(r.timer.ms("sampling"), 0.0);
  EXPECT_EQ(layer(r, "traversal_depth").channels, 1);
}

TEST(ManyLightMethod, ExtremesGiveFiniteImages) {
  Scene scene = load_default_scene();
  for (int vpls : {1, 2, 3}) {
    RenderResult r = render_frame(scene, small("uniform", 1, 8), {{"vpls", vpls}});
    for (float v : r.frame.color.data) ASSERT_TRUE(std::isfinite(v)) << vpls;
  }
  Scene dark = test::lambert_plane(0.5f, 10.0f, 3.0f, 1.0f);  // no lights: empty VPL set
  RenderResult r = render_frame(dark, small("uniform", 1, 8), {{"vpls", 10}});
  for (float v : r.frame.color.data) ASSERT_EQ(v, 0.0f);
}

}  // namespace
}  // namespace sst
