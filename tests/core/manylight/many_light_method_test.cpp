// The VPL pipeline: exhaustive VPL shading against the path tracer, and the uniform sampler's
// convergence to exhaustive on the same VPL set (per-pixel z-test with the variance image).
#include <gtest/gtest.h>

#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "tests/analytic_scenes.h"
#include "tests/core/manylight/many_light_test_util.h"

namespace sst {
namespace {

TEST(ManyLightMethod, UniformConvergesToExhaustiveOnTheSameVpls) {
  // Few VPLs and many samples: every VPL is drawn ~40 times per pixel, so the pixel means are
  // close to normal and the sample variance is a fair estimate (with hundreds of VPLs a nearby
  // one, drawn a couple of times, makes the per-pixel distribution too skewed for a z-test).
  Scene scene = load_default_scene();
  nlohmann::json vpl = {{"vpls", 24}, {"vpl_max_bounces", 3}};
  // Same seed and spp: both renders jitter their camera rays identically, so the exhaustive
  // image is exactly the expectation of the uniform one, pixel by pixel.
  RenderResult uniform = render_frame(scene, test::small_options("uniform", 1024, 16), vpl);
  RenderResult exhaustive = render_frame(scene, test::small_options("exhaustive", 1024, 16), vpl);
  Image u = test::frame_layer(uniform, "indirect"), var = test::frame_layer(uniform, "indirect_variance");
  Image e = test::frame_layer(exhaustive, "indirect");
  EXPECT_EQ(test::z_test_failures(u, var, e, 5.1), 0);
  EXPECT_EQ(uniform.frame.counters.nonfinite_samples, 0u);
}

TEST(ManyLightMethod, RecordsVplStatsAndLayers) {
  RenderResult r = render_frame(load_default_scene(), test::small_options("uniform", 2, 16), {{"vpls", 100}});
  EXPECT_EQ(r.frame.method_counters["vpl"]["vpls"], 100);
  EXPECT_GT(r.timer.ms("vpl_generation"), 0.0);
  EXPECT_GT(r.timer.ms("sampling"), 0.0);
  EXPECT_EQ(test::frame_layer(r, "traversal_depth").channels, 1);
}

TEST(ManyLightMethod, ExtremesGiveFiniteImages) {
  Scene scene = load_default_scene();
  for (int vpls : {1, 2, 3}) {
    RenderResult r = render_frame(scene, test::small_options("uniform", 1, 8), {{"vpls", vpls}});
    for (float v : r.frame.color.data) ASSERT_TRUE(std::isfinite(v)) << vpls;
  }
  Scene dark = test::lambert_plane(0.5f, 10.0f, 3.0f, 1.0f);  // no lights: empty VPL set
  RenderResult r = render_frame(dark, test::small_options("uniform", 1, 8), {{"vpls", 10}});
  for (float v : r.frame.color.data) ASSERT_EQ(v, 0.0f);
}

}  // namespace
}  // namespace sst
