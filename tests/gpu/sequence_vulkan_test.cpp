// A sequence's post-processing on the Vulkan backend (gpu/temporal_pass.h, gpu/filter_pass.h)
// against the CPU's: the same frames (the CPU traces through the flat BVH the GPU traverses), then
// temporal reuse, SVGF and half-resolution upsampling, each on its frame's backend.
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cstdio>

#include "core/pipeline/sequence.h"
#include "core/scene/default_scene.h"
#include "tests/gpu/gpu_test_util.h"

namespace sst {
namespace {

std::vector<FrameOutput> render(const std::string& backend, const nlohmann::json& paths) {
  Scene scene = load_default_scene();
  std::vector<KeyFramePath> p = parse_key_frame_paths(paths, scene, "test");
  RenderOptions o;
  o.backend = backend;
  o.accel = "flat";
  o.width = 48;
  o.height = 40;
  o.spp = 2;
  o.frames = 3;
  o.temporal = true;
  o.denoise = "svgf";
  o.indirect_scale = 2;
  std::vector<FrameOutput> frames;
  render_sequence(scene, p, o, nlohmann::json::object(), true, [&](SequenceFrame& f) {
    frames.push_back(f.result.frame);
    if (backend == "vulkan") {
      for (const char* stage : {"temporal", "denoise", "upsample"}) EXPECT_GT(f.result.timer.ms(stage), 0.0) << stage;
    }
  });
  return frames;
}

TEST(VulkanSequence, TemporalReuseSvgfAndUpsamplingEqualTheCpu) {
  SKIP_WITHOUT_GPU("temporal_accumulate");
  nlohmann::json paths = nlohmann::json::parse(
      R"([{"camera": "", "keys": [{"time": 0, "yaw_degrees": 0}, {"time": 1, "yaw_degrees": 30}]}])");
  std::vector<FrameOutput> gpu = render("vulkan", paths), cpu = render("cpu", paths);
  ASSERT_EQ(gpu.size(), cpu.size());
  for (size_t i = 0; i < gpu.size(); ++i) {
    double color = test::relative_rmse(gpu[i].color, cpu[i].color);
    double indirect = test::relative_rmse(gpu[i].indirect, cpu[i].indirect);
    std::printf("frame %zu: relative RMSE vulkan vs cpu: colour %.2e, indirect %.2e\n", i, color, indirect);
    EXPECT_LT(color, 1e-4) << "frame " << i;
    EXPECT_LT(indirect, 1e-4) << "frame " << i;
  }
}

}  // namespace
}  // namespace sst
#endif  // SST_HAVE_VULKAN
