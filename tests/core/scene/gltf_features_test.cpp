// The surface features of glTF scenes (alpha masks, BLEND, COLOR_0, normal maps) rendered on every
// backend against the image means that theory predicts (tests/core/scene/gltf_feature_scenes.h):
// the CPU with Embree (filter functions do the alpha test), the CPU with the flat BVH and, where a
// Vulkan device exists, the GPU (both through the shared traversal's alpha hook).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "core/accel/flat_bvh.h"
#include "core/lights/light_sampler.h"
#include "core/pipeline/renderer.h"
#include "core/scene/gltf_loader.h"
#include "core/vpl/vpl_generator.h"
#include "tests/core/scene/gltf_feature_scenes.h"
#include "tests/test_util.h"
#ifdef SST_HAVE_VULKAN
#include "gpu/vpl_generation_pass.h"
#include "tests/gpu/gpu_test_util.h"
#endif

namespace sst {
namespace {

struct Measured {
  vec3 mean{0.0f};
  vec3 standard_error{0.0f};  // of the mean, from the spread of the pixels (an upper bound)
  vec3 max{0.0f};             // the brightest pixel
};

constexpr int kSize = 48, kSpp = 16;

Measured measure(const Image& img) {
  glm::dvec3 sum(0.0), sum2(0.0), hi(0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      glm::dvec3 v(img.rgb(x, y));
      sum += v;
      sum2 += v * v;
      hi = glm::max(hi, v);
    }
  const double n = double(img.pixel_count());
  const glm::dvec3 mean = sum / n;
  const glm::dvec3 var = glm::max(sum2 / n - mean * mean, glm::dvec3(0.0));
  return {vec3(mean), vec3(glm::sqrt(var / (n - 1.0))), vec3(hi)};
}

std::vector<std::string> backends() {
  std::vector<std::string> out = {"cpu", "cpu-flat"};
#ifdef SST_HAVE_VULKAN
  if (test::gpu_unavailable("pt").empty()) out.push_back("vulkan");
  // The device's ray queries: alpha-masked geometry is non-opaque there, each candidate hit tested.
  std::vector<DeviceInfo> devices = list_vulkan_devices();
  if (test::gpu_unavailable("pt_rq").empty() && !devices.empty() && devices[0].ray_query)
    out.push_back("vulkan-rayquery");
#endif
  return out;
}

Measured render(const Scene& scene, const std::string& backend) {
  RenderOptions options;
  options.method = "pt";
  options.backend = backend.rfind("vulkan", 0) == 0 ? "vulkan" : "cpu";
  options.accel = backend == "cpu-flat" ? "flat" : (backend == "vulkan-rayquery" ? "rayquery" : "embree");
  options.width = kSize;
  options.height = kSize;
  options.spp = kSpp;
  options.seed = 7;
  options.diffuse_only = true;
  return measure(render_frame(scene, options, {{"max_bounces", 0}}).frame.color);
}

TEST(GltfFeatures, EveryFeatureSceneRendersItsAnalyticMeanOnEveryBackend) {
  const test::fs::path dir = test::temp_dir();
  const std::vector<test::FeatureScene> scenes = test::feature_scenes(dir);
  for (const std::string& backend : backends()) {
    std::map<std::string, Measured> done;
    for (const test::FeatureScene& f : scenes) {
      SCOPED_TRACE(backend + " " + f.name);
      const Scene scene = load_gltf(f.path.string());
      const Measured m = render(scene, backend);
      done[f.name] = m;
      if (f.reference) continue;
      // Float rounding, and the 8-bit normal texel's y of 0.0039 (a cosine off by 1e-5).
      vec3 got = m.mean, tolerance(2e-4f);
      if (!f.relative_to.empty()) {
        // A ratio of two noisy means: its standard error from both, four of them allowed.
        const Measured& ref = done.at(f.relative_to);
        got = m.mean / ref.mean;
        const vec3 rel = glm::sqrt(glm::pow(m.standard_error / m.mean, vec3(2)) +
                                   glm::pow(ref.standard_error / ref.mean, vec3(2)));
        tolerance = 4.0f * got * rel;
      } else if (f.name.rfind("mask", 0) == 0) {
        // Checker edges cut pixels, whose jittered samples (each 0 or the brightest value) make
        // the mean noisy: a sample's variance is at most max^2 / 4, so four standard errors of
        // the mean of all samples are at most 4 (max / 2) / sqrt(pixels x spp).
        tolerance += 2.0f * m.max / std::sqrt(float(kSize * kSize * kSpp));
      }
      std::printf("[gltf features] %-8s %-22s expected %.4f %.4f %.4f  measured %.4f %.4f %.4f  (+- %.4f)  %s\n",
                  backend.c_str(), f.name.c_str(), f.expected.x, f.expected.y, f.expected.z, got.x, got.y, got.z,
                  tolerance.x, f.what.c_str());
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], f.expected[c], tolerance[c]) << "channel " << c;
    }
  }
}

// Light paths (VPL generation) take the alpha test too: the sun's paths, straight down through the
// white checker screen, stop on its opaque cells and reach the floor through its holes only.
TEST(GltfFeatures, LightPathsPassTheAlphaMaskOnEveryBackend) {
  const test::fs::path dir = test::temp_dir();
  Scene scene;
  for (const test::FeatureScene& f : test::feature_scenes(dir))
    if (f.name == "mask_white") scene = load_gltf(f.path.string());
  ASSERT_FALSE(scene.triangles.empty());
  VplParams params;
  params.vpls = 4000;
  params.vpl_max_bounces = 1;  // first hits only
  EmbreeAccel embree(scene), flat(scene, true);
  LightSampler lights(scene);
  std::vector<std::pair<std::string, VplSet>> sets = {{"cpu", generate_vpls(scene, embree, lights, params, 3, true)},
                                                      {"cpu-flat", generate_vpls(scene, flat, lights, params, 3, true)}};
#ifdef SST_HAVE_VULKAN
  if (test::gpu_unavailable("vpl_generation").empty()) {
    gpu::VulkanContext context(0);
    gpu::GpuScene gpu_scene(context, scene);
    gpu::GpuBvh bvh(context, build_flat_bvh(scene));
    gpu::GpuLights gpu_lights(context, scene, lights);
    sets.emplace_back("vulkan", gpu::generate_vpls_gpu(context, gpu_scene, bvh, gpu_lights, scene, params, 3, true));
  }
#endif
  for (const auto& [backend, vpls] : sets) {
    SCOPED_TRACE(backend);
    ASSERT_EQ(vpls.size(), size_t(params.vpls));
    size_t on_screen = 0, on_floor = 0, wrong = 0;
    for (const Vpl& v : vpls) {
      const bool screen = v.position.y > 1.0f;
      (screen ? on_screen : on_floor) += 1;
      if (test::checker_opaque(v.position.x, v.position.z) != screen) ++wrong;
    }
    std::printf("[gltf features] %-8s light paths: %zu VPLs on the screen's opaque cells, %zu on the floor under "
                "its holes, %zu elsewhere\n",
                backend.c_str(), on_screen, on_floor, wrong);
    EXPECT_EQ(wrong, 0u);
    // Half the paths stop on the screen: a binomial count, five standard deviations allowed.
    EXPECT_NEAR(double(on_screen) / double(vpls.size()), 0.5, 5.0 * 0.5 / std::sqrt(double(vpls.size())));
  }
}

// Bytes that are not a Draco mesh: one line naming the file and the primitive, no crash.
TEST(GltfFeatures, CorruptDracoDataIsAnErrorNamingTheFile) {
  const test::fs::path dir = test::temp_dir();
  test::FeatureSceneBuilder f(dir);
  test::GltfBuilder b = f.base(1, vec3(0, -1, 0), test::FeatureSceneBuilder::lambert(0.5f), {}, false, true);
  const test::json& view = b.doc["bufferViews"].back();  // the Draco data, written last
  const size_t offset = view["byteOffset"], length = view["byteLength"];
  for (size_t i = offset; i < offset + length; ++i) b.bin[i] = char(b.bin[i] ^ 0x5A);
  const test::fs::path p = f.write(b, "corrupt");
  test::expect_one_line_naming(test::load_error(p), p, "mesh 0 primitive 0: the KHR_draco_mesh_compression data is not");
}

// The same Draco floor packed into a GLB (whose JSON chunk the loader rewrites for tinygltf)
// loads as the glTF does.
TEST(GltfFeatures, DracoInAGlbLoadsAsInAGltf) {
  const test::fs::path dir = test::temp_dir();
  test::FeatureSceneBuilder f(dir);
  test::GltfBuilder b = f.base(1, vec3(0, -1, 0), test::FeatureSceneBuilder::lambert(0.5f), {}, false, true);
  const Scene gltf = load_gltf(f.write(b, "floor").string());
  const Scene glb = load_gltf(b.write_glb(dir, "floor").string());
  ASSERT_EQ(gltf.triangles.size(), 2u);
  EXPECT_EQ(glb.positions, gltf.positions);
  EXPECT_EQ(glb.triangles, gltf.triangles);
  EXPECT_EQ(glb.uvs, gltf.uvs);
  EXPECT_EQ(glb.gltf_features, (std::vector<std::string>{"KHR_draco_mesh_compression"}));
}

}  // namespace
}  // namespace sst
