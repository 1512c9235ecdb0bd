// The `pt` method on the GPU (gpu/path_trace_pass.h, gpu/shaders/pt.comp) against the CPU's
// (render_frame, backend cpu, method pt) from the same seed.
//
// Where the two backends trace the same rays, the images agree to float-order differences
// (issue 5's bar: RMSE below 1e-3 of the CPU image's mean): the direct light everywhere, and every
// layer of the Cornell boxes for max_bounces 0, 1 and the default. Counters: primary rays and
// samples exactly; shadow and bounce rays to a small fraction.
//
// Where they do not: the CPU traces with Embree, the GPU with the flat BVH, and the surface points
// they report differ in the last bits (Embree's barycentrics are not the flat BVH's); the GPU's
// sin/cos also differ from glibc's by an ulp (core/sampling/sampling.h, core/material/brdf.h). A path that
// grazes an edge after such a difference takes another course, and on the real scenes, with their
// hundreds of thousands of small triangles (and the breakfast room's coplanar, z-fighting floor),
// measured on lavapipe: 0.3% (staircase) / 0.9% (breakfast room) of the camera paths with one
// bounce, 4% of them with the default eight, each then an equally valid, different sample. The
// pixel means of the indirect light then agree only statistically: those tests bound how many
// pixels such paths reach and how far the image means move, and keep the strict bar for the
// direct layer (whose camera rays and shadow rays agree).
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cmath>
#include <cstdio>

#include "core/accel/embree_accel.h"
#include "core/accel/flat_bvh.h"
#include "core/lights/light_sampler.h"
#include "core/render/camera.h"
#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "gpu/path_trace_pass.h"
#include "tests/analytic_scenes.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"

namespace sst::gpu {
namespace {

using test::relative_rmse;
constexpr auto mean = test::image_mean;

double relative_mean_difference(const Image& gpu, const Image& cpu) {
  double m = mean(cpu);
  return m > 0.0 ? std::abs(mean(gpu) - m) / m : std::abs(mean(gpu));
}

// Fraction of pixels whose colour differs by more than 1e-3 relative: reached by a path that took
// another course on one backend.
double diverged_fraction(const Image& gpu, const Image& cpu) {
  size_t n = 0;
  for (int y = 0; y < cpu.height; ++y)
    for (int x = 0; x < cpu.width; ++x) {
      vec3 g = gpu.rgb(x, y), c = cpu.rgb(x, y);
      n += max_component(glm::abs(g - c)) > 1e-3f * std::max(1e-3f, max_component(c));
    }
  return double(n) / (double(cpu.width) * double(cpu.height));
}

double relative_difference(uint64_t gpu, uint64_t cpu) {
  return cpu > 0 ? std::abs(double(gpu) - double(cpu)) / double(cpu) : double(gpu);
}

struct Case {
  int width;
  int spp;
  uint32_t seed;
  int max_bounces;
  const char* light_sampler = "power";
};

// What one GPU render differs by from the CPU's; the tests assert on it.
struct Comparison {
  double color = 0, direct = 0, indirect = 0, albedo = 0, depth = 0;  // relative RMSE
  double diverged = 0;                          // fraction of pixels (colour)
  double color_mean = 0, indirect_mean = 0;     // relative difference of the image means
  double shadow_rays = 0, bounce_rays = 0;      // relative difference of the counts
  double cpu_indirect_mean = 0;
  RayCounters gpu, cpu;
  uint64_t expected_primary_rays = 0;
  int dispatches = 0;
};

Comparison compare_pt(const Scene& scene, const Case& c) {
  RenderOptions options;
  options.method = "pt";
  options.width = c.width;
  options.spp = c.spp;
  options.seed = c.seed;
  options.light_sampler = c.light_sampler;
  PathTracerParams params;
  params.max_bounces = c.max_bounces;
  RenderResult cpu = render_frame(scene, options, {{"max_bounces", c.max_bounces}});
  const int w = cpu.options.width, h = cpu.options.height;

  VulkanContext context(0);
  GpuScene gpu_scene(context, scene);
  GpuBvh bvh(context, build_flat_bvh(scene));
  LightSampler light_sampler(scene, parse_light_sampler(c.light_sampler));
  GpuLights lights(context, scene, light_sampler);
  PinholeCamera camera(select_camera(scene, ""), w, h);
  GpuPathTraceResult gpu = render_path_tracer(context, gpu_scene, bvh, lights, scene_ray_epsilon(scene), camera, w, h,
                                              options.seed, options.spp, params, render_flags(options));

  const FrameOutput& g = gpu.frame;
  const FrameOutput& f = cpu.frame;
  Comparison r;
  r.color = relative_rmse(g.color, f.color);
  r.direct = relative_rmse(g.direct, f.direct);
  r.indirect = relative_rmse(g.indirect, f.indirect);
  r.albedo = relative_rmse(g.albedo, f.albedo);
  r.depth = relative_rmse(g.depth, f.depth);
  r.diverged = diverged_fraction(g.color, f.color);
  r.color_mean = relative_mean_difference(g.color, f.color);
  r.indirect_mean = relative_mean_difference(g.indirect, f.indirect);
  r.cpu_indirect_mean = mean(f.indirect);
  r.gpu = g.counters;
  r.cpu = f.counters;
  r.shadow_rays = relative_difference(g.counters.shadow_rays, f.counters.shadow_rays);
  r.bounce_rays = relative_difference(g.counters.bounce_rays, f.counters.bounce_rays);
  r.expected_primary_rays = uint64_t(w) * uint64_t(h) * uint64_t(c.spp);
  r.dispatches = gpu.dispatches;
  std::printf(
      "%s %s %dx%d %d spp max_bounces %d: relative RMSE color %.2e direct %.2e indirect %.2e albedo %.2e depth %.2e; "
      "%.2f%% of pixels diverged; means differ by %.1e (color) %.1e (indirect); rays primary %llu/%llu shadow "
      "%llu/%llu (%.1e) bounce %llu/%llu (%.1e); nonfinite %llu/%llu; GPU %.1f ms in %d dispatches (%s)\n",
      scene.source.c_str(), c.light_sampler, w, h, c.spp, c.max_bounces, r.color, r.direct, r.indirect, r.albedo, r.depth,
      100.0 * r.diverged, r.color_mean, r.indirect_mean, (unsigned long long)g.counters.primary_rays,
      (unsigned long long)f.counters.primary_rays, (unsigned long long)g.counters.shadow_rays,
      (unsigned long long)f.counters.shadow_rays, r.shadow_rays, (unsigned long long)g.counters.bounce_rays,
      (unsigned long long)f.counters.bounce_rays, r.bounce_rays, (unsigned long long)g.counters.nonfinite_samples,
      (unsigned long long)f.counters.nonfinite_samples, gpu.gpu_ms, gpu.dispatches, context.info().name.c_str());
  return r;
}

// Every camera sample is one primary ray and one sample, on both backends; shadow and bounce rays
// differ only by the paths that took another course.
void expect_counters(const Comparison& r, double ray_tolerance) {
  EXPECT_EQ(r.gpu.primary_rays, r.cpu.primary_rays);
  EXPECT_EQ(r.gpu.primary_rays, r.expected_primary_rays);
  EXPECT_EQ(r.gpu.samples, r.cpu.samples);
  EXPECT_EQ(r.gpu.nonfinite_samples, r.cpu.nonfinite_samples);
  EXPECT_EQ(r.gpu.nonfinite_samples, 0u);
  EXPECT_LE(r.shadow_rays, ray_tolerance);
  EXPECT_LE(r.bounce_rays, ray_tolerance);
  EXPECT_GT(r.gpu.shadow_rays, 0u);
}

// Issue 5's bar on every layer.
void expect_float_order_only(const Comparison& r, int max_bounces) {
  EXPECT_LT(r.color, 1e-3);
  EXPECT_LT(r.direct, 1e-3);
  if (max_bounces > 0) {
    EXPECT_GT(r.cpu_indirect_mean, 0.0);
    EXPECT_LT(r.indirect, 1e-3);
  } else {
    EXPECT_EQ(r.indirect, 0.0);  // both black
  }
  EXPECT_LT(r.albedo, 1e-3);
  EXPECT_LT(r.depth, 1e-3);
  expect_counters(r, 1e-3);
}

// ---- the Cornell box: the strict bar for every bounce count ------------------------------------

TEST(GpuPathTracer, EqualsTheCpuOnTheCornellBoxDirectOnly) {
  SKIP_WITHOUT_GPU("pt");
  Comparison r = compare_pt(load_default_scene(), {64, 8, 7, 0});
  expect_float_order_only(r, 0);
  EXPECT_GT(r.dispatches, 1);  // the samples were split into chunks
}

TEST(GpuPathTracer, EqualsTheCpuOnTheCornellBoxOneBounce) {
  SKIP_WITHOUT_GPU("pt");
  expect_float_order_only(compare_pt(load_default_scene(), {64, 8, 7, 1}), 1);
}

TEST(GpuPathTracer, EqualsTheCpuOnTheCornellBoxDefaultBounces) {
  SKIP_WITHOUT_GPU("pt");
  const int bounces = PathTracerParams{}.max_bounces;
  expect_float_order_only(compare_pt(load_default_scene(), {64, 8, 7, bounces}), bounces);
}

// Delta lights: the shared Cornell box lit by a point light instead of the lamp, and the built-in
// one with a point, a spot and a directional light added to its lamp. Direct light meets the bar;
// with a bounce, the one path in ~10^5 whose course the GPU's sin/cos change (a 1-ulp difference
// from glibc's) may leave one pixel apart, so the indirect light is held to the image means and
// to that handful of pixels.
void expect_point_lit(const Comparison& r, int max_bounces) {
  if (max_bounces == 0) return expect_float_order_only(r, 0);
  EXPECT_LT(r.direct, 1e-3);
  EXPECT_LT(r.albedo, 1e-3);
  EXPECT_LT(r.depth, 1e-3);
  EXPECT_GT(r.cpu_indirect_mean, 0.0);
  EXPECT_LT(r.diverged, 2e-3);
  EXPECT_LT(r.indirect_mean, 1e-3);
  EXPECT_LT(r.color_mean, 1e-3);
  expect_counters(r, 1e-3);
}

TEST(GpuPathTracer, EqualsTheCpuOnThePointLitCornellBox) {
  SKIP_WITHOUT_GPU("pt");
  auto path = test::shared_scene("cornell-box/cornell-box-point.gltf");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes absent";
  Scene scene = load_gltf(path.string());
  ASSERT_FALSE(scene.lights.empty());
  for (int bounces : {0, 1}) expect_point_lit(compare_pt(scene, {64, 4, 5, bounces}), bounces);
}

TEST(GpuPathTracer, EqualsTheCpuWithEveryPunctualLightType) {
  SKIP_WITHOUT_GPU("pt");
  Scene scene = load_default_scene();
  vec3 c = scene.bounds.center();
  float r = 0.5f * scene.bounds.diagonal();
  PunctualLight point, spot, sun;
  point.type = LightType::Point;
  point.position = c + vec3(0.2f * r, 0.3f * r, 0.1f * r);
  point.intensity = vec3(0.4f, 0.3f, 0.2f);
  spot.type = LightType::Spot;
  spot.position = c + vec3(-0.2f * r, 0.35f * r, 0.0f);
  spot.direction = glm::normalize(vec3(0.2f, -1.0f, 0.1f));
  spot.intensity = vec3(1.0f);
  spot.cos_inner = std::cos(0.3f);
  spot.cos_outer = std::cos(0.6f);
  sun.type = LightType::Directional;  // through the box's open front
  sun.direction = glm::normalize(vec3(0.1f, -0.3f, -1.0f));
  sun.intensity = vec3(0.5f, 0.6f, 0.7f);
  scene.lights = {point, spot, sun};
  for (int bounces : {0, 1}) expect_point_lit(compare_pt(scene, {48, 4, 9, bounces}), bounces);
}

// Many small emitters, points, spots and a sun: every light sampler picks the same lights on both
// backends (tests/gpu/light_sampler_gpu_test.cpp checks the picks bit for bit), so direct light
// meets the bar; with a bounce, as for the point-lit box above.
TEST(GpuPathTracer, EqualsTheCpuWithEveryLightSampler) {
  SKIP_WITHOUT_GPU("pt");
  Scene scene = test::many_lights(8, 1500, 6, 6, true);
  for (const char* sampler : {"uniform", "tree", "slc"}) {
    SCOPED_TRACE(sampler);
    for (int bounces : {0, 1}) expect_point_lit(compare_pt(scene, {48, 4, 11, bounces, sampler}), bounces);
  }
}

// ---- real scenes: the strict bar where the backends trace the same rays ------------------------

// Direct light only: camera and shadow rays agree, so every layer meets the bar (albedo aside
// where z-fighting geometry shows a different one of two coplanar triangles).
void expect_direct_only(const Comparison& r, double albedo_bound) {
  EXPECT_LT(r.color, 1e-3);
  EXPECT_LT(r.direct, 1e-3);
  EXPECT_EQ(r.indirect, 0.0);
  EXPECT_LT(r.albedo, albedo_bound);
  EXPECT_LT(r.depth, 1e-3);
  expect_counters(r, 1e-3);
}

// With bounces: the direct layer meets the bar; the indirect light agrees statistically (see the
// top of the file), with bounds from the measurements on lavapipe (in brackets) and room for
// another device's rounding.
void expect_diverging_paths(const Comparison& r, double max_diverged, double max_mean_difference) {
  EXPECT_LT(r.direct, 1e-3);
  EXPECT_GT(r.cpu_indirect_mean, 0.0);
  EXPECT_LT(r.diverged, max_diverged);
  EXPECT_LT(r.indirect_mean, max_mean_difference);
  EXPECT_LT(r.color_mean, max_mean_difference);
  expect_counters(r, 2e-3);
}

Scene shared_scene_or_skip(const char* relative, bool* found) {
  auto path = test::shared_scene(relative);
  *found = !path.empty();
  return *found ? load_gltf(path.string()) : Scene{};
}

TEST(GpuPathTracer, StaircaseDirectLightEqualsTheCpu) {
  SKIP_WITHOUT_GPU("pt");
  bool found = false;
  Scene scene = shared_scene_or_skip("staircase/staircase.gltf", &found);
  if (!found) GTEST_SKIP() << "../shared/scenes absent";
  expect_direct_only(compare_pt(scene, {48, 4, 11, 0}), 1e-3);
}

TEST(GpuPathTracer, StaircaseWithBouncesAgreesUpToDivergingPaths) {
  SKIP_WITHOUT_GPU("pt");
  bool found = false;
  Scene scene = shared_scene_or_skip("staircase/staircase.gltf", &found);
  if (!found) GTEST_SKIP() << "../shared/scenes absent";
  expect_diverging_paths(compare_pt(scene, {48, 4, 11, 1}), 0.05, 0.05);
  expect_diverging_paths(compare_pt(scene, {48, 4, 11, PathTracerParams{}.max_bounces}), 0.3, 0.05);
}

TEST(GpuPathTracer, BreakfastRoomDirectLightEqualsTheCpu) {
  SKIP_WITHOUT_GPU("pt");
  bool found = false;
  Scene scene = shared_scene_or_skip("breakfast-room/breakfast-room-point.gltf", &found);
  if (!found) GTEST_SKIP() << "../shared/scenes absent";
  expect_direct_only(compare_pt(scene, {64, 4, 11, 0}), 0.1);
}

TEST(GpuPathTracer, BreakfastRoomWithBouncesAgreesUpToDivergingPaths) {
  SKIP_WITHOUT_GPU("pt");
  bool found = false;
  Scene scene = shared_scene_or_skip("breakfast-room/breakfast-room-point.gltf", &found);
  if (!found) GTEST_SKIP() << "../shared/scenes absent";
  expect_diverging_paths(compare_pt(scene, {64, 4, 11, 1}), 0.05, 0.05);
  expect_diverging_paths(compare_pt(scene, {64, 4, 11, PathTracerParams{}.max_bounces}), 0.3, 0.05);
}

// The wavefront (gpu/shaders/pt_wavefront.comp) runs the megakernel's stages in the same order per
// path and adds the samples in the same order: the same bits in every layer, the same ray counts,
// with a wave smaller than the image (kPathWavePaths) exercised by an image larger than one wave.
TEST(GpuPathTracer, WavefrontIsTheSameBitsAsTheMegakernel) {
  SKIP_WITHOUT_GPU("pt_wavefront_0");
  struct Setting {
    Scene scene;
    int width, height, spp, max_bounces;
  };
  std::vector<Setting> settings;
  settings.push_back({load_default_scene(), 40, 24, 3, PathTracerParams{}.max_bounces});
  settings.push_back({load_default_scene(), 300, 240, 1, 1});  // 72000 paths: two waves
  settings.push_back({test::emissive_box(0.8f, 1.0f, 2.0f), 24, 16, 2, 5});
  for (const Setting& s : settings) {
    RenderOptions options;
    options.method = "pt";
    options.backend = "vulkan";
    options.width = s.width;
    options.height = s.height;
    options.spp = s.spp;
    options.seed = 17;
    const nlohmann::json params = {{"max_bounces", s.max_bounces}, {"rr_min_bounces", 1}};
    options.gpu_paths = "megakernel";
    RenderResult mega = render_frame(s.scene, options, params);
    options.gpu_paths = "wavefront";
    RenderResult wave = render_frame(s.scene, options, params);
    SCOPED_TRACE(std::to_string(s.width) + "x" + std::to_string(s.height));
    EXPECT_EQ(mega.frame.color.data, wave.frame.color.data);
    EXPECT_EQ(mega.frame.direct.data, wave.frame.direct.data);
    EXPECT_EQ(mega.frame.indirect.data, wave.frame.indirect.data);
    EXPECT_EQ(mega.frame.albedo.data, wave.frame.albedo.data);
    EXPECT_EQ(mega.frame.normal.data, wave.frame.normal.data);
    EXPECT_EQ(mega.frame.depth.data, wave.frame.depth.data);
    EXPECT_EQ(mega.frame.counters.shadow_rays, wave.frame.counters.shadow_rays);
    EXPECT_EQ(mega.frame.counters.bounce_rays, wave.frame.counters.bounce_rays);
    EXPECT_EQ(mega.frame.counters.samples, wave.frame.counters.samples);
    EXPECT_GT(wave.frame.counters.bounce_rays, 0u);
  }
}

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
