// Issue 5's acceptance test: every method renders on --backend vulkan (lavapipe in CI) and its
// image equals the CPU backend's from the same seed, to float-order differences: RMSE below 1e-3
// of the CPU image's mean, on the built-in Cornell box and on a real scene.
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/pipeline/renderer.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/util/error.h"
#include "tests/analytic_scenes.h"
#include "tests/core/manylight/many_light_test_util.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"

namespace sst {
namespace {

using test::relative_rmse;

const Image* layer(const FrameOutput& f, const std::string& name) {
  for (const Layer& l : f.extra_layers)
    if (l.name == name) return &l.image;
  return nullptr;
}

// Block z-test of the indirect layers (Mitsuba-style, with the renders' own variance images): per
// 8x8 block, the difference of the mean luminances over its standard error. Returns the fraction
// of blocks with |z| > 3.29 (p = 0.001 each) and, in *z_all, the z of the whole image.
double fraction_of_outlier_blocks(const FrameOutput& a, const FrameOutput& b, double* z_all) {
  const Image *va = layer(a, "indirect_variance"), *vb = layer(b, "indirect_variance");
  if (!va || !vb) {
    ADD_FAILURE() << "no indirect_variance layer to test against";
    return 1.0;
  }
  const Image &ia = a.indirect, &ib = b.indirect;
  auto lum = [](const Image& img, int x, int y) {
    return 0.2126 * img.at(x, y, 0) + 0.7152 * img.at(x, y, 1) + 0.0722 * img.at(x, y, 2);
  };
  int outliers = 0, blocks = 0;
  double diff_all = 0.0, var_all = 0.0;
  for (int by = 0; by < ia.height; by += 8)
    for (int bx = 0; bx < ia.width; bx += 8) {
      double diff = 0.0, var = 0.0;
      for (int y = by; y < std::min(by + 8, ia.height); ++y)
        for (int x = bx; x < std::min(bx + 8, ia.width); ++x) {
          diff += lum(ia, x, y) - lum(ib, x, y);
          var += lum(*va, x, y) + lum(*vb, x, y);
        }
      diff_all += diff;
      var_all += var;
      ++blocks;
      if (var > 0.0 ? std::abs(diff) / std::sqrt(var) > 3.29 : std::abs(diff) > 1e-6) ++outliers;
    }
  *z_all = var_all > 0.0 ? diff_all / std::sqrt(var_all) : 0.0;
  return double(outliers) / double(blocks);
}

// How a method's Vulkan image is held to the CPU's:
//   exact: RMSE below 1e-3 of the mean, against the CPU on the same flat BVH (--accel flat).
//          Every kernel of a frame is one source for both backends (core/math/cpu_gpu.h), so on
//          lavapipe the images are equal bit for bit (relative RMSE 0); the bar leaves room for
//          devices whose sqrt and division are not correctly rounded;
//   statistical: the block z-test above, plus the direct layer exact: for the CPU's Embree
//          traversal, whose hits differ from the flat BVH's in the last bits.
enum class Agreement { exact, statistical };
struct Case {
  std::string method;
  nlohmann::json params;
  Agreement cornell, real_scene;
  std::string light_sampler = "power";
};

// rtslc's direct light from cuts of the emitter tree (rtslc_direct.h), walked by `sampler`.
Case rtslc_direct_cuts(const std::string& sampler) {
  return {"rtslc", {{"vpls", 512}, {"interleave", 2}, {"direct_light", "cuts"}}, Agreement::exact, Agreement::exact,
          sampler};
}

// pt, every VPL method of the list with 2048 VPLs (exhaustive, whose cost grows with them, 64),
// and variants that take other paths through a method's kernels.
std::vector<Case> cases() {
  std::vector<Case> cases = {{"pt", {{"max_bounces", 2}}, Agreement::exact, Agreement::exact}};
  for (const std::string& m : test::many_light_method_names())
    cases.push_back({m, {{"vpls", m == "exhaustive" ? 64 : 2048}}, Agreement::exact, Agreement::exact});
  cases.push_back({"rtslc", {{"vpls", 2048}, {"interleave", 2}, {"weights", "slc"}}, Agreement::exact, Agreement::exact});
  cases.push_back(rtslc_direct_cuts("tree"));
  return cases;
}

RenderResult render(const Scene& scene, const Case& c, const std::string& backend, const std::string& accel,
                    int spp) {
  RenderOptions options;
  options.method = c.method;
  options.width = 48;
  options.spp = spp;
  options.seed = 7;
  options.backend = backend;
  options.accel = accel;
  options.light_sampler = c.light_sampler;
  return render_frame(scene, options, c.params);
}

// The block z-test's verdict: at most 5% outlier blocks, and the whole image within |z| < 3.29.
void expect_statistical_agreement(const FrameOutput& gpu, const FrameOutput& cpu, const std::string& label) {
  double z_all = 0.0;
  double outliers = fraction_of_outlier_blocks(gpu, cpu, &z_all);
  std::printf("%s statistical: %.1f%% of 8x8 blocks with |z| > 3.29, whole-image z %.2f\n", label.c_str(),
              100.0 * outliers, z_all);
  EXPECT_LE(outliers, 0.05);
  EXPECT_LT(std::abs(z_all), 3.29);
}

void expect_backends_agree(const Scene& scene, const Case& c, Agreement agreement) {
  const int spp = agreement == Agreement::exact ? 2 : 8;
  RenderResult cpu = render(scene, c, "cpu", "flat", spp), gpu = render(scene, c, "vulkan", "flat", spp);
  ASSERT_EQ(gpu.device["backend"], "vulkan");
  double color = relative_rmse(gpu.frame.color, cpu.frame.color);
  double direct = relative_rmse(gpu.frame.direct, cpu.frame.direct);
  double indirect = relative_rmse(gpu.frame.indirect, cpu.frame.indirect);
  std::string name = scene.source.substr(scene.source.find_last_of('/') + 1);
  std::string params = c.params.dump() + (c.light_sampler == "power" ? "" : " --light-sampler " + c.light_sampler);
  std::printf("%-26s %-10s %-48s relative RMSE vulkan vs cpu: color %.2e direct %.2e indirect %.2e\n", name.c_str(),
              c.method.c_str(), params.c_str(), color, direct, indirect);
  EXPECT_LT(direct, 1e-3);
  EXPECT_EQ(gpu.frame.counters.primary_rays, cpu.frame.counters.primary_rays);
  EXPECT_EQ(gpu.frame.counters.samples, cpu.frame.counters.samples);
  EXPECT_EQ(gpu.frame.counters.nonfinite_samples, 0u);
  if (agreement == Agreement::exact) {
    EXPECT_LT(color, 1e-3);
    EXPECT_LT(indirect, 1e-3);
    return;
  }
  char label[64];
  std::snprintf(label, sizeof label, "%-26s %-10s", name.c_str(), c.method.c_str());
  expect_statistical_agreement(gpu.frame, cpu.frame, label);
}

TEST(VulkanBackend, EveryMethodMatchesTheCpuOnTheCornellBox) {
  SKIP_WITHOUT_GPU("many_light");
  Scene scene = load_default_scene();
  for (const Case& c : cases()) expect_backends_agree(scene, c, c.cornell);
}

// RTSLC's real-light case: thousands of emissive triangles, point, spot and directional lights.
TEST(VulkanBackend, RtslcDirectCutsMatchTheCpuAmongManyLights) {
  SKIP_WITHOUT_GPU("many_light");
  Scene scene = test::many_lights(8, 1500, 6, 6, true);
  for (const char* sampler : {"tree", "slc"}) expect_backends_agree(scene, rtslc_direct_cuts(sampler), Agreement::exact);
}

TEST(VulkanBackend, EveryMethodMatchesTheCpuOnTheBreakfastRoom) {
  SKIP_WITHOUT_GPU("many_light");
  auto path = test::shared_scene("breakfast-room/breakfast-room-point.gltf");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes absent";
  Scene scene = load_gltf(path.string());
  for (const Case& c : cases()) expect_backends_agree(scene, c, c.real_scene);
}

// BRSM VPLs (vpl_source brsm, gpu/brsm_pass.h) give the CPU's images: on the Cornell box (an
// emissive quad) for the methods that differ in how they read a VPL set (slc walks a tree of it,
// sst its substitutes, hybrid shares cuts), on the breakfast room (a sun, the thesis's light) and
// on a scene of many lights of every kind, where lights share maps. (Every method on every scene:
// 190 s on two cores, for the same VPL sets.)
TEST(VulkanBackend, BrsmVplsGiveTheCpuImages) {
  SKIP_WITHOUT_GPU("brsm");
  auto brsm = [](const std::string& method) {
    return Case{method,
                {{"vpl_source", "brsm"}, {"vpls", 2048}, {"brsm_resolution", 64}},
                Agreement::exact,
                Agreement::exact};
  };
  Scene cornell = load_default_scene();
  for (const char* m : {"slc", "sst", "hybrid"}) expect_backends_agree(cornell, brsm(m), Agreement::exact);
  expect_backends_agree(test::many_lights(8, 300, 3, 3, true), brsm("slc"), Agreement::exact);
  auto path = test::shared_scene("breakfast-room/breakfast-room.gltf");
  if (!path.empty()) expect_backends_agree(load_gltf(path.string()), brsm("slc"), Agreement::exact);
}

// Light paths bounce toward the view from outside the focus sphere (core/vpl/light_path_bounce.h):
// the window room's grey ground reaches beyond the sphere (2 x the view's median distance about
// the camera), and the images are still the CPU's. The case does take that branch: without it
// the CPU's image differs.
TEST(VulkanBackend, FocusedBouncesGiveTheCpuImages) {
  SKIP_WITHOUT_GPU("many_light");
  Scene room = load_gltf(std::string(SST_SOURCE_DIR) + "/scenes/window-room-10km.gltf");
  const Case focused{"slc", {{"vpls", 2048}}, Agreement::exact, Agreement::exact};
  expect_backends_agree(room, focused, Agreement::exact);
  Case cosine = focused;
  cosine.params["focus_bounces"] = 0.0;
  EXPECT_GT(relative_rmse(render(room, cosine, "cpu", "flat", 2).frame.indirect,
                          render(room, focused, "cpu", "flat", 2).frame.indirect),
            1e-3);
}

// The node-distance floor made to act on the 10 km room (whose VPLs span under 50 view lengths):
// the whole frame, host side included, gives the CPU's images with every tree method.
TEST(VulkanBackend, NodeDistanceFloorGivesTheCpuImages) {
  SKIP_WITHOUT_GPU("many_light");
  Scene room = load_gltf(std::string(SST_SOURCE_DIR) + "/scenes/window-room-10km.gltf");
  for (const char* method : {"slc", "sst", "rtslc", "hybrid"}) {
    SCOPED_TRACE(method);
    const Case floored{method, {{"vpls", 2048}, {"node_distance_floor_above", 0.0}}, Agreement::exact, Agreement::exact};
    expect_backends_agree(room, floored, Agreement::exact);
  }
}

// Against the default CPU backend (Embree): different barycentrics and edge decisions move VPLs
// and paths, so agreement is statistical there.
TEST(VulkanBackend, SstAgreesStatisticallyWithTheEmbreeCpu) {
  SKIP_WITHOUT_GPU("many_light");
  auto path = test::shared_scene("breakfast-room/breakfast-room-point.gltf");
  if (path.empty()) GTEST_SKIP() << "../shared/scenes absent";
  Scene scene = load_gltf(path.string());
  Case c{"sst", {{"vpls", 2048}}, Agreement::statistical, Agreement::statistical};
  RenderResult cpu = render(scene, c, "cpu", "embree", 8), gpu = render(scene, c, "vulkan", "embree", 8);
  expect_statistical_agreement(gpu.frame, cpu.frame, "sst vulkan vs embree cpu:");
}

TEST(VulkanBackend, RecordNamesTheDeviceAndWhereEachStageRan) {
  SKIP_WITHOUT_GPU("many_light");
  RenderOptions options;
  options.method = "sst";
  options.backend = "vulkan";
  options.width = 16;
  options.spp = 1;
  RenderResult r = render_frame(load_default_scene(), options, {{"vpls", 256}});
  EXPECT_FALSE(r.device["name"].get<std::string>().empty());
  EXPECT_EQ(r.device["setup"]["bvh"]["built_on"], "cpu");
  EXPECT_EQ(r.frame.method_counters["built_on"]["tree"], "gpu");  // sst's radix tree
  EXPECT_EQ(r.frame.method_counters["tree"]["built_on"], "gpu");
  EXPECT_EQ(r.frame.method_counters["built_on"]["sampling"], "gpu");
  EXPECT_GT(r.frame.method_counters["gpu_ms"]["sampling"].get<double>(), 0.0);
  EXPECT_GT(r.timer.ms("gpu_setup"), 0.0);
  // rtslc's perfect tree is built on the GPU, its cuts on the CPU; an agglomerative tree on the CPU.
  options.method = "rtslc";
  RenderResult rt = render_frame(load_default_scene(), options, {{"vpls", 256}});
  EXPECT_EQ(rt.frame.method_counters["built_on"]["tree"], "gpu");
  EXPECT_EQ(rt.frame.method_counters["built_on"]["cuts"], "cpu");
  options.method = "slc";
  RenderResult ag = render_frame(load_default_scene(), options, {{"vpls", 256}, {"tree", "agglomerative"}});
  EXPECT_EQ(ag.frame.method_counters["built_on"]["tree"], "cpu");
}

// An exhaustive sum over more VPLs than lavapipe's loop limit lets one invocation shade is split
// into slices of VPLs, one dispatch each; the slices continue one running sum, so the image keeps
// the CPU's bits.
TEST(VulkanBackend, ExhaustiveOverManyVplsMatchesTheCpu) {
  SKIP_WITHOUT_GPU("many_light");
  Scene scene = load_default_scene();
  Case c{"exhaustive", {{"vpls", 4096}}, Agreement::exact, Agreement::exact};
  RenderOptions options;
  options.method = c.method;
  options.width = 20;
  options.spp = 1;
  options.seed = 7;
  options.accel = "flat";
  RenderResult cpu = render_frame(scene, options, c.params);
  options.backend = "vulkan";
  RenderResult gpu = render_frame(scene, options, c.params);
  double color = relative_rmse(gpu.frame.color, cpu.frame.color);
  int dispatches = gpu.frame.method_counters["gpu"]["sampling_dispatches"];
  std::printf("exhaustive, 4096 VPLs: %d sampling dispatches, relative RMSE vulkan vs cpu %.2e\n", dispatches, color);
  EXPECT_LT(color, 1e-3);
  EXPECT_EQ(gpu.frame.counters.shadow_rays, cpu.frame.counters.shadow_rays);
  EXPECT_EQ(gpu.frame.counters.nonfinite_samples, 0u);
  if (gpu.device.value("type", "") == "cpu") {
    EXPECT_GT(dispatches, 1);
  }
}

// --accel rayquery: the shaders trace the device's acceleration structures instead of the flat
// BVH. The surfaces are the same; which of two triangles a ray meets on a shared edge or a
// coplanar overlap may differ (tie-breaking is the driver's), so the first hits are compared
// pixel by pixel and the images statistically.
std::string ray_query_unavailable() {
  std::string why = test::gpu_unavailable("pt_rq");
  if (!why.empty()) return why;
  for (const DeviceInfo& d : list_vulkan_devices(nullptr))
    if (d.index == 0 && !d.ray_query) return d.name + " has no ray queries (VK_KHR_ray_query)";
  return "";
}
#define SKIP_WITHOUT_RAY_QUERY()                  \
  do {                                            \
    std::string why = ray_query_unavailable();    \
    if (!why.empty()) GTEST_SKIP() << why;        \
  } while (0)

// Camera rays (pt with no bounce, 1 spp: the same jittered ray per pixel on both): the pixels
// whose first hit is another surface, told by its depth and albedo.
TEST(VulkanRayQuery, FirstHitsAreTheFlatBvhsAwayFromEdges) {
  SKIP_WITHOUT_RAY_QUERY();
  for (const char* name : {"cornell-box", "breakfast-room/breakfast-room-point.gltf", "staircase/staircase.gltf"}) {
    Scene scene;
    if (std::string(name) == "cornell-box") {
      scene = load_default_scene();
    } else {
      auto path = test::shared_scene(name);
      if (path.empty()) continue;
      scene = load_gltf(path.string());
    }
    Case c{"pt", {{"max_bounces", 0}}, Agreement::statistical, Agreement::statistical};
    RenderOptions options;
    options.method = "pt";
    options.width = 96;
    options.spp = 1;
    options.seed = 3;
    options.backend = "vulkan";
    options.accel = "flat";
    RenderResult flat = render_frame(scene, options, c.params);
    options.accel = "rayquery";
    RenderResult rq = render_frame(scene, options, c.params);
    ASSERT_EQ(rq.device["setup"]["accel"], "rayquery");
    const Image &da = flat.frame.depth, &db = rq.frame.depth;
    int differ = 0, hits = 0;
    for (int y = 0; y < da.height; ++y)
      for (int x = 0; x < da.width; ++x) {
        float a = da.at(x, y, 0), b = db.at(x, y, 0);
        if (a > 0.0f || b > 0.0f) ++hits;
        // The driver's barycentrics and distances differ from the flat BVH's in the last bits,
        // which moves texture lookups by as little: another surface shows as another depth or
        // a different albedo or normal.
        bool same = std::abs(a - b) <= 1e-4f * std::max(a, b);
        for (int k = 0; k < 3; ++k) {
          same = same && std::abs(flat.frame.albedo.at(x, y, k) - rq.frame.albedo.at(x, y, k)) <= 1e-3f;
          same = same && std::abs(flat.frame.normal.at(x, y, k) - rq.frame.normal.at(x, y, k)) <= 1e-3f;
        }
        if (!same) ++differ;
      }
    std::printf("%-42s camera rays whose first hit differs from the flat BVH's: %d of %d hits (%.3f%%)\n", name,
                differ, hits, hits ? 100.0 * differ / hits : 0.0);
    EXPECT_GT(hits, 0);
    EXPECT_LE(differ, hits / 100) << name;  // edges and overlaps only
    EXPECT_EQ(rq.frame.counters.nonfinite_samples, 0u);
  }
}

// Every kind of kernel on ray queries (pt's paths, VPL generation, the many-light direct pass
// and shadow rays, rtslc's cuts) against the CPU on the flat BVH. pt's paths draw the same random
// numbers on both, so its images differ only where a hit does (the bar: 5% relative RMSE, 15x
// the 3.4e-3 measured on the breakfast room); a VPL set whose light paths moved by last bits builds other trees, so the
// VPL methods are held to the block z-test of their indirect layers.
TEST(VulkanRayQuery, MethodsAgreeWithTheCpu) {
  SKIP_WITHOUT_RAY_QUERY();
  auto path = test::shared_scene("breakfast-room/breakfast-room-point.gltf");
  Scene scene = path.empty() ? load_default_scene() : load_gltf(path.string());
  for (const Case& c : {Case{"pt", {{"max_bounces", 2}}, Agreement::statistical, Agreement::statistical},
                        Case{"sst", {{"vpls", 2048}}, Agreement::statistical, Agreement::statistical},
                        Case{"rtslc", {{"vpls", 2048}}, Agreement::statistical, Agreement::statistical}}) {
    RenderResult cpu = render(scene, c, "cpu", "flat", 8), gpu = render(scene, c, "vulkan", "rayquery", 8);
    ASSERT_EQ(gpu.device["setup"]["accel"], "rayquery");
    double direct = relative_rmse(gpu.frame.direct, cpu.frame.direct);
    double color = relative_rmse(gpu.frame.color, cpu.frame.color);
    std::printf("%-6s rayquery vs cpu: relative RMSE color %.2e direct %.2e\n", c.method.c_str(), color, direct);
    EXPECT_LT(direct, 0.05) << c.method;
    EXPECT_EQ(gpu.frame.counters.nonfinite_samples, 0u);
    EXPECT_EQ(gpu.frame.counters.primary_rays, cpu.frame.counters.primary_rays);
    if (c.method == "pt") {
      EXPECT_LT(color, 0.05);
      continue;
    }
    expect_statistical_agreement(gpu.frame, cpu.frame, c.method + " rayquery vs cpu:");
  }
}

TEST(VulkanRayQuery, RecordHasTheAccelerationStructure) {
  SKIP_WITHOUT_RAY_QUERY();
  RenderOptions options;
  options.method = "pt";
  options.width = 16;
  options.spp = 1;
  options.backend = "vulkan";
  options.accel = "rayquery";
  RenderResult r = render_frame(load_default_scene(), options, {{"max_bounces", 0}});
  const nlohmann::json& as = r.device["setup"]["acceleration_structure"];
  EXPECT_EQ(as["triangles"], 36);
  EXPECT_GT(as["bottom_level_bytes"].get<double>(), 0.0);
  EXPECT_GT(as["top_level_bytes"].get<double>(), 0.0);
  EXPECT_EQ(r.options.accel, "rayquery");
  options.backend = "cpu";
  EXPECT_THROW(render_frame(load_default_scene(), options, {{"max_bounces", 0}}), Error);
}

}  // namespace
}  // namespace sst
#endif  // SST_HAVE_VULKAN
