// The G-buffer stage on the GPU against the CPU's first-hit AOVs from the same seed: the AOVs of
// the path tracer (albedo, normal, depth) must agree to float-order differences.
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cmath>

#include "core/metrics/metrics.h"
#include "core/pipeline/backend.h"
#include "core/render/camera.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "gpu/gbuffer_pass.h"
#include "gpu/shader_library.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"

namespace sst::gpu {
namespace {

using test::relative_rmse;

void expect_gbuffer_equals_cpu(const Scene& scene, int width) {
  SKIP_WITHOUT_GPU("gbuffer");
  RenderOptions options;
  options.method = "pt";
  options.width = width;
  options.spp = 4;
  options.seed = 3;
  RenderResult cpu = render_frame(scene, options, {{"max_bounces", 0}});
  const int w = cpu.options.width, h = cpu.options.height;
  VulkanContext context(0);
  GpuScene gpu_scene(context, scene);
  GpuBvh bvh(context, build_flat_bvh(scene));
  PinholeCamera camera(select_camera(scene, ""), w, h);
  GBufferImages g = render_gbuffer(context, gpu_scene, bvh, camera, w, h, options.seed, options.spp);
  double albedo = relative_rmse(g.albedo, cpu.frame.albedo), normal = relative_rmse(g.normal, cpu.frame.normal),
         depth = relative_rmse(g.depth, cpu.frame.depth);
  std::printf("%s %dx%d, %d spp: relative RMSE GPU vs CPU: albedo %.2e, normal %.2e, depth %.2e; GPU %.2f ms (%s)\n",
              scene.source.c_str(), w, h, options.spp, albedo, normal, depth, g.gpu_ms, context.info().name.c_str());
  // Float-order differences only (the backends' bar: RMSE below 1e-3 of the image mean).
  EXPECT_LT(albedo, 1e-3);
  EXPECT_LT(normal, 1e-3);
  EXPECT_LT(depth, 1e-3);
}

TEST(GpuGBuffer, EqualsTheCpuAovsOnTheCornellBox) { expect_gbuffer_equals_cpu(load_default_scene(), 96); }

TEST(GpuGBuffer, EqualsTheCpuAovsOnTheStaircase) {
  auto path = test::shared_scene("staircase/staircase.gltf");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes absent";
  expect_gbuffer_equals_cpu(load_gltf(path.string()), 72);
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
