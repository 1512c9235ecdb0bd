// ReSTIR DI and ReSTIR GI on the Vulkan backend (gpu/restir_pass.h) against the CPU's (core/restir/
// restir_di.cpp) on the same flat BVH: one source, the same stages in the same order, so lavapipe
// gives the CPU's bits (the bar, relative RMSE below 1e-3, leaves room for GPUs whose sqrt and
// division are not correctly rounded). Every kind of method takes its direct light from it:
// pt, a VPL method, and rtslc, whose own direct cuts it replaces. (Two light samplers only: each
// compiles the three stages again, minutes on a cold lavapipe cache.)
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cstdio>
#include <filesystem>
#include <string>

#include "core/pipeline/renderer.h"
#include "core/pipeline/sequence.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/key_frame_path.h"
#include "core/scene/default_scene.h"
#include "tests/analytic_scenes.h"
#include "tests/core/eval/eval_test_util.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"

namespace sst {
namespace {

struct Case {
  std::string method;
  nlohmann::json params;
  std::string light_sampler;
  const char* combine;
  int spatial_passes;
};

RenderResult render(const Scene& scene, const Case& c, bool diffuse_only, const std::string& backend) {
  RenderOptions o;
  o.method = c.method;
  o.width = 40;
  o.height = 32;
  o.spp = 2;
  o.seed = 11;
  o.backend = backend;
  o.accel = "flat";
  o.diffuse_only = diffuse_only;
  o.light_sampler = c.light_sampler;
  o.direct_sampler = "restir";
  o.restir.combine = c.combine;
  o.restir.spatial_passes = c.spatial_passes;
  o.restir.candidates = 8;
  return render_frame(scene, o, c.params);
}

void expect_backends_agree(const Scene& scene, bool diffuse_only, const Case& c) {
  RenderResult cpu = render(scene, c, diffuse_only, "cpu"), gpu = render(scene, c, diffuse_only, "vulkan");
  ASSERT_EQ(gpu.device["backend"], "vulkan");
  double color = test::relative_rmse(gpu.frame.color, cpu.frame.color);
  double direct = test::relative_rmse(gpu.frame.direct, cpu.frame.direct);
  std::printf("%-8s %-34s %-7s %-8s passes %d: relative RMSE vulkan vs cpu: color %.2e direct %.2e\n",
              c.method.c_str(), c.params.dump().c_str(), c.light_sampler.c_str(), c.combine, c.spatial_passes, color,
              direct);
  EXPECT_LT(direct, 1e-3);
  EXPECT_LT(color, 1e-3);
  EXPECT_EQ(gpu.frame.counters.shadow_rays, cpu.frame.counters.shadow_rays);
  EXPECT_EQ(gpu.frame.counters.bounce_rays, cpu.frame.counters.bounce_rays);
  EXPECT_EQ(gpu.frame.counters.nonfinite_samples, 0u);
}

TEST(RestirDiVulkan, MatchesTheCpuAmongManyLights) {
  SKIP_WITHOUT_GPU("restir_1");
  Scene scene = test::many_lights(31, 400, 5, 5, true);
  for (const Case& c : {Case{"pt", {{"max_bounces", 1}}, "power", "unbiased", 2},
                        Case{"pt", {{"max_bounces", 0}}, "power", "biased", 1},
                        Case{"rtslc", {{"vpls", 256}, {"interleave", 2}, {"direct_light", "cuts"}}, "tree", "unbiased", 1}})
    expect_backends_agree(scene, true, c);
}

TEST(RestirDiVulkan, MatchesTheCpuOnTheGlossyCornellBox) {
  SKIP_WITHOUT_GPU("restir_1");
  Scene scene = load_default_scene();
  for (const Case& c : {Case{"pt", {{"max_bounces", 2}}, "power", "unbiased", 1},
                        Case{"sst", {{"vpls", 512}}, "power", "unbiased", 1}})
    expect_backends_agree(scene, false, c);
}

// The camera turning 20 degrees a second.
const char* const kTurning = R"([{"camera": "", "keys": [{"time": 0}, {"time": 1, "yaw_degrees": 20}]}])";

// Three frames (40x32) of `o` on the CPU and on Vulkan, both on the flat BVH, with the key-frame
// paths `paths_json`: every frame's colour equals.
void expect_sequences_agree(const Scene& scene, RenderOptions o, const nlohmann::json& params, const char* label,
                            const char* paths_json = kTurning) {
  std::vector<KeyFramePath> paths = parse_key_frame_paths(nlohmann::json::parse(paths_json), scene, "test");
  auto frames = [&](const std::string& backend) {
    o.width = 40;
    o.height = 32;
    o.frames = 3;
    o.backend = backend;
    o.accel = "flat";
    std::vector<Image> out;
    Scene posed = scene;
    render_sequence(posed, paths, o, params, true, [&](SequenceFrame& f) { out.push_back(f.result.frame.color); });
    return out;
  };
  std::vector<Image> cpu = frames("cpu"), gpu = frames("vulkan");
  ASSERT_EQ(cpu.size(), 3u);
  ASSERT_EQ(gpu.size(), 3u);
  for (size_t f = 0; f < cpu.size(); ++f) {
    double color = test::relative_rmse(gpu[f], cpu[f]);
    std::printf("%s, frame %zu: relative RMSE vulkan vs cpu %.2e\n", label, f, color);
    EXPECT_LT(color, 1e-3) << label << ", frame " << f;
  }
}

// Temporal reuse through a turning camera (every frame of a sequence reprojects the last one's
// reservoirs) and under moving lights (every frame is posed anew: the history comes back to the
// new device context and is evaluated in the new pose), the same way on both backends.
TEST(RestirDiVulkan, SequencesWithTemporalReuseMatchTheCpu) {
  SKIP_WITHOUT_GPU("restir_1");
  RenderOptions o;
  o.method = "pt";
  o.spp = 1;
  o.diffuse_only = true;
  o.direct_sampler = "restir";
  o.restir.candidates = 8;
  expect_sequences_agree(test::many_lights(31, 400, 5, 5, true), o, {{"max_bounces", 0}}, "restir di");
  expect_sequences_agree(test::many_lights(32, 40, 4, 0, false), o, {{"max_bounces", 0}}, "restir di, moving lights",
                         R"([{"light": "0", "keys": [{"time": 0, "translate": [0, 0, 0]}, {"time": 0.1, "translate": [1.2, 0, 0.4]}]},
                             {"light": "1", "keys": [{"time": 0, "translate": [0, 0, 0]}, {"time": 0.1, "translate": [-1, 0, 0]}]}])");
}

// restir_gi's validation in a moving scene (scenes/animated_box.gltf: the box and camera slide, the
// light moves): the history's vertices found again and their paths traced the same way.
TEST(RestirGiVulkan, MovingSceneMatchesTheCpu) {
  SKIP_WITHOUT_GPU("restir_5");
  RenderOptions o;
  o.method = "restir_gi";
  o.spp = 1;
  o.diffuse_only = true;
  expect_sequences_agree(load_gltf(std::string(SST_SOURCE_DIR) + "/scenes/animated_box.gltf"), o, {{"max_bounces", 2}},
                         "restir_gi, moving scene",
                         R"([{"light": "0", "keys": [{"time": 0, "translate": [0, 0, 0]}, {"time": 0.1, "translate": [1.5, 0, 0]}]}])");
}

// On Vulkan the histories live on the device: a checkpoint reads them back, and a resumed run
// hands them to a new device. Runs with ReSTIR DI's temporal reuse and with restir_gi resume with
// the numbers and image of the uninterrupted run.
TEST(RestirGiVulkan, SequenceRunsWithReservoirHistoriesResume) {
  SKIP_WITHOUT_GPU("restir_4");
  for (const nlohmann::json& fields :
       {nlohmann::json{{"method", "pt"}, {"max_bounces", 1}, {"spp", 1}, {"direct_sampler", "restir"}, {"backend", "vulkan"}},
        nlohmann::json{{"method", "restir_gi"}, {"max_bounces", 2}, {"spp", 1}, {"backend", "vulkan"}}}) {
    SCOPED_TRACE(fields.dump());
    std::filesystem::path dir = test::temp_dir();
    test::expect_resumes(test::tiny_sequence_run(fields), (dir / "whole").string(), (dir / "cut").string());
  }
}

// restir_gi's secondary paths and reuse, through a sequence with a turning camera, diffuse and
// glossy.
TEST(RestirGiVulkan, MatchesTheCpu) {
  SKIP_WITHOUT_GPU("restir_4");
  for (bool diffuse_only : {true, false}) {
    RenderOptions o;
    o.method = "restir_gi";
    o.spp = 2;
    o.diffuse_only = diffuse_only;
    expect_sequences_agree(load_default_scene(), o, {{"max_bounces", 2}}, diffuse_only ? "restir_gi diffuse" : "restir_gi");
  }
}

}  // namespace
}  // namespace sst

#endif  // SST_HAVE_VULKAN
