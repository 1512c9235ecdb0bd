// The filters on the GPU (gpu/filter_pass.h) against the CPU's (core/filter/filters.h) on the same
// inputs: the Cornell box's noisy demodulated indirect light with its G-buffer, and the analytic
// two-plane edge with a sky band. The kernels are one text; only exp/pow and the order of float
// operations may differ, so the images agree to relative RMSE 1e-4.
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cstdio>

#include "core/filter/filters.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "gpu/filter_pass.h"
#include "tests/core/filter/filter_test_images.h"
#include "tests/gpu/gpu_test_util.h"

namespace sst::gpu {
namespace {

using test::relative_rmse;

struct Inputs {
  Image light, depth, normal, moments, history;
  Image low, low_depth, low_normal;  // half resolution, point-sampled
};

Inputs cornell_box_inputs() {
  RenderOptions options;
  options.method = "pt";
  options.width = 64;
  options.spp = 2;
  options.seed = 9;
  RenderResult r = render_frame(load_default_scene(), options, nlohmann::json::object());
  Inputs in;
  in.light = demodulate(r.frame.indirect, r.frame.albedo);
  in.depth = r.frame.depth;
  in.normal = r.frame.normal;
  return in;
}

Inputs two_plane_inputs() {
  test::TwoPlanes t = test::two_planes(40, 24, vec3(0.05f, 0.04f, 0.03f), vec3(0.5f, 0.4f, 0.3f), 0.5f, 0.5f, 5, 3);
  Inputs in;
  in.light = t.color;
  in.depth = t.depth;
  in.normal = t.normal;
  return in;
}

void complete(Inputs& in, float history) {
  in.moments = test::single_frame_moments(in.light);
  in.history = test::constant_image(in.light.width, in.light.height, 1, history);
  in.low = test::point_downsample(in.light, 2);
  in.low_depth = test::point_downsample(in.depth, 2);
  in.low_normal = test::point_downsample(in.normal, 2);
}

void expect_gpu_equals_cpu(Inputs in, const char* what) {
  VulkanContext context(0);
  FilteredImage atrous = atrous_filter(context, in.light, in.depth, in.normal, AtrousParams{});
  Image atrous_cpu = sst::atrous_filter(in.light, in.depth, in.normal, AtrousParams{});
  // History 1 takes SVGF's spatial variance estimate, 8 its temporal one.
  double svgf_error[2], level1_error[2], variance_error[2];
  for (int h = 0; h < 2; ++h) {
    complete(in, h == 0 ? 1.0f : 8.0f);
    SvgfSpatialImages svgf = svgf_spatial(context, in.light, in.moments, in.history, in.depth, in.normal, SvgfParams{});
    SvgfSpatialResult svgf_cpu = sst::svgf_spatial(in.light, in.moments, in.history, in.depth, in.normal, SvgfParams{});
    svgf_error[h] = relative_rmse(svgf.filtered, svgf_cpu.filtered);
    level1_error[h] = relative_rmse(svgf.level1, svgf_cpu.level1);
    variance_error[h] = relative_rmse(svgf.variance, svgf_cpu.variance);
  }
  FilteredImage up = joint_bilateral_upsample(context, in.low, in.low_depth, in.low_normal, in.depth, in.normal,
                                              UpsampleParams{});
  Image up_cpu = sst::joint_bilateral_upsample(in.low, in.low_depth, in.low_normal, in.depth, in.normal, UpsampleParams{});
  const double atrous_error = relative_rmse(atrous.image, atrous_cpu), up_error = relative_rmse(up.image, up_cpu);
  std::printf("%s %dx%d: relative RMSE GPU vs CPU: atrous %.2e, svgf %.2e / %.2e (history 1 / 8; level 1 %.2e, "
              "variance %.2e), upsample %.2e (%s)\n",
              what, in.light.width, in.light.height, atrous_error, svgf_error[0], svgf_error[1], level1_error[0],
              variance_error[0], up_error, context.info().name.c_str());
  EXPECT_LT(atrous_error, 1e-4);
  for (int h = 0; h < 2; ++h) {
    EXPECT_LT(svgf_error[h], 1e-4);
    EXPECT_LT(level1_error[h], 1e-4);
    EXPECT_LT(variance_error[h], 1e-4);
  }
  EXPECT_LT(up_error, 1e-4);
}

TEST(GpuFilter, EqualsTheCpuOnTheCornellBox) {
  SKIP_WITHOUT_GPU("filter_svgf");
  expect_gpu_equals_cpu(cornell_box_inputs(), "cornell box");
}

TEST(GpuFilter, EqualsTheCpuOnTwoPlanesAndSky) {
  SKIP_WITHOUT_GPU("filter_svgf");
  expect_gpu_equals_cpu(two_plane_inputs(), "two planes");
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
