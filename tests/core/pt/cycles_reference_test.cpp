// The path tracer against an independent renderer (Blender Cycles, ../shared/scenes): the CI
// version of the acceptance check. The built-in scene is the shared Cornell box, so the shared
// references apply. Noise is compared at equal samples per pixel and equal size: stratified
// samplers (ours: Owen-scrambled Sobol; Cycles: progressive multi-jitter) converge faster than
// 1/sqrt(spp), so error ratios at unequal spp say little.
#include <gtest/gtest.h>

#include "core/image/image.h"
#include "core/metrics/metrics.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "tests/test_util.h"

namespace sst {
namespace {

TEST(CyclesReference, CornellBoxDiffuseMatchesMeansAndNoiseLevel) {
  auto ref_path = test::shared_scene("cornell-box/ref/cornell-box_4096spp_seed1.exr");
  auto low_path = test::shared_scene("cornell-box/ref/cornell-box_256spp_seed2.exr");
  if (ref_path.empty() || low_path.empty()) GTEST_SKIP() << "../shared/scenes not present";
  Image reference = read_image(ref_path.string());
  Image cycles_low = read_image(low_path.string());

  RenderOptions options;
  options.width = options.height = 256;
  options.spp = 256;
  options.diffuse_only = true;
  options.seed = 1;
  RenderResult r = render_frame(load_default_scene(), options, {{"max_bounces", 8}});
  ImageMetrics ours = compare_images(r.frame.color, reference);
  ImageMetrics cycles = compare_images(cycles_low, reference);

  // Per-channel means within 1% (the noise of a mean over 65k pixels is far below that).
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(ours.mean_test[c], ours.mean_reference[c], 0.01 * ours.mean_reference[c]) << "channel " << c;
  // The same spp as Cycles' second render: its error against the reference is what an equally
  // good renderer achieves. Within 10% of it, as the issue asks.
  EXPECT_LT(ours.rmse, 1.1 * cycles.rmse) << "ours " << ours.rmse << " cycles " << cycles.rmse;
  EXPECT_EQ(r.frame.counters.nonfinite_samples, 0u);
  RecordProperty("rmse_ours", std::to_string(ours.rmse));
  RecordProperty("rmse_cycles_256spp", std::to_string(cycles.rmse));
}

}  // namespace
}  // namespace sst
