// The GPU indirect samplers (gpu/shaders/indirect_sampler.glsl) against the CPU's
// IndirectSampler::estimate, on the same inputs: the Cornell box, one VPL set, each sampler's
// prepare() run on the CPU and its inputs() uploaded, the shading points of the CPU's
// camera hits (one sample per pixel), and each pixel sampler continued on the GPU from where the
// CPU's ManyLightMethod hands it to estimate(). Per point, the GPU must draw the same random sets,
// visit the same nodes and trace the same shadow rays, and its value must equal the CPU's to float
// precision; over the points, the RMSE must be below 1e-3 of the mean (issue 5's bar).
#include <gtest/gtest.h>
#ifdef SST_HAVE_VULKAN

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "core/accel/flat_bvh.h"
#include "core/manylight/many_light_method.h"
#include "core/manylight/shading_point.h"
#include "core/manylight/sampler_inputs.h"
#include "core/pipeline/method_registry.h"
#include "core/pt/path_tracer.h"
#include "core/scene/default_scene.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gbuffer_pass.h"
#include "gpu/many_light_upload.h"
#include "tests/core/manylight/many_light_test_util.h"
#include "tests/gpu/gpu_test_util.h"

namespace sst::gpu {
namespace {

// The C++ twins of the structs of gpu/shaders/indirect_sampler_test.comp.
struct IndirectTestPoint {
  vec3 p;
  uint32_t seed;
  vec3 ng;
  uint32_t pixel;
  vec3 t;
  uint32_t sample_index;
  vec3 b;
  uint32_t sets_used;
  vec3 n;
  int32_t x;
  vec3 wo;
  int32_t y;
  vec3 diffuse;
  float alpha;
  vec3 f0;
  uint32_t specular;
  float depth;
  uint32_t pad[3];
};
static_assert(sizeof(IndirectTestPoint) == 144 && offsetof(IndirectTestPoint, depth) == 128);

struct IndirectTestResult {
  vec3 value;
  uint32_t nodes_visited;
  uint32_t shadow_rays;
  uint32_t sets_used;
  uint32_t pad0, pad1;
};
static_assert(sizeof(IndirectTestResult) == 32);

struct TestPush {
  uint32_t count;
  float ray_epsilon;
};

constexpr int kWidth = 48, kHeight = 32;
constexpr uint32_t kSeed = 7;


// The Cornell box, diffuse-only or made glossy (rough dielectric walls, one metal: both lobes and
// the pure-metal case of sst), its VPLs and the shading points of sample 0 of every pixel, each
// with its pixel sampler advanced as ManyLightMethod advances it (jitter, then trace_path's
// draws) before it calls estimate().
struct TestFrame {
  Scene scene;
  std::unique_ptr<EmbreeAccel> accel;
  std::unique_ptr<LightSampler> lights;
  std::unique_ptr<PinholeCamera> camera;
  RenderOptions options;
  std::unique_ptr<RenderContext> context;
  VplSet vpls;
  float clamp_distance = 0.0f, clamp_per_depth = 0.0f;
  FlatBvh bvh;
  std::vector<ShadingPoint> points;
  std::vector<PixelSampler> samplers;
  std::vector<uint32_t> pixels;

  TestFrame(bool diffuse_only, int vpl_count) : scene(load_default_scene()) {
    if (!diffuse_only)
      for (size_t i = 0; i < scene.materials.size(); ++i) {
        scene.materials[i].roughness = 0.3f + 0.1f * float(i % 3);
        scene.materials[i].metallic = i == 3 ? 1.0f : 0.0f;
      }
    accel = std::make_unique<EmbreeAccel>(scene);
    lights = std::make_unique<LightSampler>(scene);
    camera = std::make_unique<PinholeCamera>(select_camera(scene, ""), kWidth, kHeight);
    options.width = kWidth;
    options.height = kHeight;
    options.seed = kSeed;
    options.diffuse_only = diffuse_only;
    context = std::make_unique<RenderContext>(RenderContext{scene, *accel, *lights, *camera, options, kWidth, kHeight, true});
    if (vpl_count > 0) {
      VplParams vp;
      vp.vpls = vpl_count;
      VplStats stats;
      vpls = generate_vpls(scene, *accel, *lights, vp, kSeed, diffuse_only, &stats);
      clamp_distance = stats.clamp_distance;
      clamp_per_depth = stats.clamp_per_depth;
    }
    bvh = build_flat_bvh(scene);
    trace_points();
  }

  void trace_points() {
    PathTracerParams direct_only;
    direct_only.max_bounces = 0;
    RayCounters rc;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        uint32_t pixel = uint32_t(y) * uint32_t(kWidth) + uint32_t(x);
        PixelSampler sampler = pixel_sampler(kSeed, pixel, 0);
        vec2 jitter = pixel_sampler_get2d(sampler);
        Ray ray = camera->generate(float(x) + jitter.x, float(y) + jitter.y);
        Surface hit;
        PathSample d = trace_path(*context, direct_only, ray, sampler, rc, &hit);
        if (!(d.depth > 0.0f)) continue;
        points.push_back(shading_point(hit, ray.direction, d.depth, options.diffuse_only, x, y));
        samplers.push_back(sampler);
        pixels.push_back(pixel);
      }
  }

  VplLighting frame() const {
    return {*context, vpls, clamp_distance, clamp_per_depth, median_view_distance(*context)};
  }
};

const TestFrame& test_frame(bool diffuse_only, int vpl_count) {
  static std::map<std::pair<bool, int>, std::unique_ptr<TestFrame>> frames;
  auto& f = frames[{diffuse_only, vpl_count}];
  if (!f) f = std::make_unique<TestFrame>(diffuse_only, vpl_count);
  return *f;
}

const VulkanContext& vulkan() {
  static VulkanContext context(0);
  return context;
}

std::vector<IndirectTestPoint> pack_points(const TestFrame& f) {
  std::vector<IndirectTestPoint> out(f.points.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const ShadingPoint& s = f.points[i];
    IndirectTestPoint& q = out[i];
    q = {};
    q.p = s.p;
    q.ng = s.ng;
    q.t = s.basis.t;
    q.b = s.basis.b;
    q.n = s.basis.n;
    q.wo = s.wo;
    q.diffuse = s.brdf.diffuse;
    q.f0 = s.brdf.f0;
    q.alpha = s.brdf.alpha;
    q.specular = s.brdf.specular ? 1u : 0u;
    q.x = s.x;
    q.y = s.y;
    q.depth = s.depth;
    q.seed = kSeed;
    q.pixel = f.pixels[i];
    q.sample_index = 0;
    q.sets_used = f.samplers[i].sets_used;
  }
  return out;
}

std::vector<IndirectTestResult> run_gpu(const TestFrame& f, const SamplerInputs& inputs) {
  const VulkanContext& context = vulkan();
  GpuManyLightInputs ml(context, inputs);
  GpuBvh bvh(context, f.bvh);
  std::vector<IndirectTestPoint> points = pack_points(f);
  GpuBuffer point_buffer(context, points.size() * sizeof(IndirectTestPoint));
  point_buffer.upload(std::span<const IndirectTestPoint>(points));
  GpuBuffer result_buffer(context, points.size() * sizeof(IndirectTestResult));
  std::vector<const GpuBuffer*> buffers = ml.buffers();
  for (const GpuBuffer* b : bvh.buffers()) buffers.push_back(b);
  buffers.push_back(&point_buffer);
  buffers.push_back(&result_buffer);
  TestPush push{uint32_t(points.size()), scene_ray_epsilon(f.scene)};
  ComputePipeline pipeline(context, "indirect_sampler_test", uint32_t(buffers.size()), sizeof push);
  pipeline.dispatch(buffers, &push, (uint32_t(points.size()) + 63) / 64);
  std::vector<IndirectTestResult> results(points.size());
  result_buffer.download(std::span<IndirectTestResult>(results));
  return results;
}

// One sampler configuration on one frame: method `method` of the registry with `params`. kVpls:
// 300, not a power of two, so that the perfect trees have padding leaves; 0, 1 and 3 VPLs are the
// degenerate sets (no tree, a lone leaf).
constexpr int kVpls = 300;
struct Case {
  std::string name;
  bool diffuse_only;
  int vpls;
  std::string method;
  nlohmann::json params;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

// Every VPL method of the list with its default parameters on the glossy frame and on the
// degenerate sets, and variants that take other paths through a method's kernels.
std::vector<Case> cases() {
  std::vector<Case> cases;
  const nlohmann::json defaults = nlohmann::json::object();
  for (const std::string& m : test::many_light_method_names()) {
    cases.push_back({m, false, kVpls, m, defaults});
    cases.push_back({"no_vpls_" + m, false, 0, m, defaults});
    cases.push_back({"one_vpl_" + m, false, 1, m, defaults});
    cases.push_back({"three_vpls_" + m, false, 3, m, defaults});
  }
  std::vector<Case> variants = {
      {"slc_perfect_tree", false, kVpls, "slc", {{"tree", "perfect"}}},
      {"sst_diffuse_only", true, kVpls, "sst", defaults},
      {"sst_no_substitutes", false, kVpls, "sst", {{"substitutes", false}}},
      {"sst_agglomerative", true, kVpls, "sst", {{"tree", "agglomerative"}}},
      {"rtslc_interleave2", false, kVpls, "rtslc", {{"interleave", 2}}},
      {"rtslc_interleave4", false, kVpls, "rtslc", {{"interleave", 4}}},
      {"rtslc_slc_weights", true, kVpls, "rtslc", {{"weights", "slc"}}},
      {"rtslc_block_size1", false, kVpls, "rtslc", {{"interleave", 2}, {"block_size", 1}}},
      {"hybrid_diffuse_only", true, kVpls, "hybrid", defaults},
      {"hybrid_mock_cut", false, kVpls, "hybrid", {{"n_min", 1.0}}},
      {"hybrid_one_block", false, kVpls, "hybrid", {{"block_size", 1000}}},
      {"slc_node_floor", false, kVpls, "slc", {{"node_distance_floor", 0.5}, {"node_distance_floor_above", 0.0}}},
      {"sst_node_floor", false, kVpls, "sst", {{"node_distance_floor", 0.5}, {"node_distance_floor_above", 0.0}}},
      {"rtslc_node_floor", false, kVpls, "rtslc", {{"node_distance_floor", 0.5}, {"node_distance_floor_above", 0.0}}},
      {"rtslc_slc_weights_node_floor", false, kVpls, "rtslc", {{"weights", "slc"}, {"node_distance_floor", 0.5}, {"node_distance_floor_above", 0.0}}},
      {"hybrid_node_floor", false, kVpls, "hybrid", {{"node_distance_floor", 0.5}, {"node_distance_floor_above", 0.0}}},
  };
  cases.insert(cases.end(), variants.begin(), variants.end());
  return cases;
}

// How the GPU's estimates agree with the CPU's at the same points.
struct Agreement {
  size_t points = 0, lit = 0;  // lit: the CPU's estimate is non-zero
  size_t sets_differ = 0, nodes_differ = 0, rays_differ = 0;
  size_t values_differ = 0;      // relative difference above 1e-4
  double worst_agreeing = 0.0;   // largest relative difference of the others
  double rmse_over_mean = 0.0;   // over all points and channels
  double nodes_per_point = 0.0, rays_per_point = 0.0;
};

Agreement compare_with_cpu(const TestFrame& f, const IndirectSampler& sampler, const VplLighting& lighting,
                           const std::vector<IndirectTestResult>& gpu) {
  Agreement a;
  a.points = f.points.size();
  double sum_abs = 0.0, sum_sq_diff = 0.0;
  for (size_t i = 0; i < a.points; ++i) {
    PixelSampler s = f.samplers[i];
    IndirectEstimate e = sampler.estimate(f.points[i], s);
    const IndirectTestResult& g = gpu[i];
    a.sets_differ += g.sets_used != s.sets_used;
    a.nodes_differ += g.nodes_visited != e.nodes_visited;
    a.rays_differ += g.shadow_rays != e.shadow_rays;
    a.nodes_per_point += e.nodes_visited;
    a.rays_per_point += e.shadow_rays;
    a.lit += max_component(e.value) > 0.0f;
    double point_error = 0.0;
    for (int k = 0; k < 3; ++k) {
      double cv = e.value[k], diff = std::abs(double(g.value[k]) - cv);
      sum_abs += std::abs(cv);
      sum_sq_diff += diff * diff;
      point_error = std::max(point_error, diff / std::max(std::abs(cv), 1e-30));
    }
    // Float precision: a few ulps per operation along the estimate.
    if (point_error > 1e-4)
      ++a.values_differ;
    else
      a.worst_agreeing = std::max(a.worst_agreeing, point_error);
  }
  double n = double(a.points);
  a.rmse_over_mean = std::sqrt(sum_sq_diff / (3.0 * n)) / std::max(sum_abs / (3.0 * n), 1e-30);
  a.nodes_per_point /= n;
  a.rays_per_point /= n;
  return a;
}

class GpuIndirectSampler : public ::testing::TestWithParam<Case> {};

TEST_P(GpuIndirectSampler, EqualsTheCpuEstimatePerShadingPoint) {
  SKIP_WITHOUT_GPU("indirect_sampler_test");
  const Case& c = GetParam();
  const TestFrame& f = test_frame(c.diffuse_only, c.vpls);
  VplLighting lighting = f.frame();
  // The method owns its sampler; its VPL parameters go unused (the frame brings the VPLs).
  std::unique_ptr<Method> method = create_method(c.method, c.params);
  IndirectSampler& sampler = dynamic_cast<ManyLightMethod&>(*method).sampler();
  StageTimer timer;
  nlohmann::json counters;
  sampler.prepare(lighting, timer, counters);
  Agreement a = compare_with_cpu(f, sampler, lighting, run_gpu(f, sampler.inputs()));
  std::printf(
      "%-20s %zu points (%zu lit), %.2f nodes and %.2f shadow rays per point: differ in sets %zu, nodes %zu, "
      "shadow rays %zu, value %zu (others within %.1e relative); RMSE / mean %.2e\n",
      c.name.c_str(), a.points, a.lit, a.nodes_per_point, a.rays_per_point, a.sets_differ, a.nodes_differ, a.rays_differ,
      a.values_differ, a.worst_agreeing, a.rmse_over_mean);
  ASSERT_GT(a.points, 500u);
  if (c.vpls == 0) {
    EXPECT_EQ(a.lit, 0u);
  } else if (c.vpls == kVpls) {
    ASSERT_GT(a.lit, a.points / 5) << "the test needs lit points";
  }
  // The same decisions at every point but for float ties of the weights (none on lavapipe).
  EXPECT_LE(a.sets_differ, a.points / 200);
  EXPECT_LE(a.nodes_differ, a.points / 200);
  EXPECT_LE(a.rays_differ, a.points / 200);
  // Values: equal to float precision except where a decision differed or the flat BVH and Embree
  // disagree on a grazing shadow ray (none on lavapipe).
  EXPECT_LE(a.values_differ, a.points / 100);
  EXPECT_LT(a.rmse_over_mean, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, GpuIndirectSampler, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

}  // namespace
}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
