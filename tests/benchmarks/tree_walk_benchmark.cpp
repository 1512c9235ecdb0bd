// The light-tree walk of slc and sst (slc_estimate.h, sst_estimate.h) at 10k and 100k VPLs in the
// breakfast room lit by its point light (../shared/scenes; the Cornell box when it is absent),
// on one thread: the "walk step" cost.
//
// Shading points are the camera hits of one sample per pixel at 160x90, each with its pixel
// sampler advanced as ManyLightMethod advances it. The tree is built once. Three variants:
//   BM_TreeWalk       estimate() as the renderer calls it: the walk, then the chosen VPL shaded
//                     with a shadow ray through the scene.
//   BM_TreeWalkNoScene  the same walks with the shadow rays traced in a one-triangle scene far
//                     away, so that what remains is the walk (plus one VPL's shading per sample).
//   BM_TreeWalkNoSceneMaterials  BM_TreeWalkNoScene with the scene's own materials, where the
//                     others take every surface as diffuse: sst then walks its glossy lobe too,
//                     as sst-render does by default, with the BRDF in each node's weight.
// Counters: ns_per_sample, nodes_per_sample, and ns_per_step = time / nodes visited.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <utility>

#include "core/lights/light_sampler.h"
#include "core/manylight/many_light_method.h"
#include "core/manylight/shading_point.h"
#include "core/manylight/slc/slc_sampler.h"
#include "core/manylight/sst/sst_sampler.h"
#include "core/pt/path_tracer.h"
#include "core/render/camera.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/vpl/vpl_generator.h"

namespace {

constexpr int kWidth = 160, kHeight = 90;
constexpr uint32_t kSeed = 3;

sst::Scene far_triangle() {
  sst::Scene s;
  s.source = "generated:far-triangle";
  s.positions = {{1e6f, 1e6f, 1e6f}, {1e6f + 1.0f, 1e6f, 1e6f}, {1e6f, 1e6f + 1.0f, 1e6f}};
  s.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  s.uvs.assign(3, sst::vec2(0.0f));
  s.triangles = {{0u, 1u, 2u}};
  s.triangle_material = {0u};
  s.materials.resize(1);
  s.finalize_bounds();
  return s;
}

// The scene, its VPLs and the shading points; shared by every benchmark of one VPL count.
struct Frame {
  sst::Scene scene, empty;
  std::unique_ptr<sst::EmbreeAccel> accel, empty_accel;
  std::unique_ptr<sst::LightSampler> lights;
  std::unique_ptr<sst::PinholeCamera> camera;
  sst::RenderOptions options;
  std::unique_ptr<sst::RenderContext> context, empty_context;
  sst::VplSet vpls;
  float clamp_distance = 0.0f, clamp_per_depth = 0.0f, view_distance = 0.0f;
  std::vector<sst::ShadingPoint> points;
  std::vector<sst::PixelSampler> samplers;

  Frame(int vpl_count, bool diffuse_only) : scene(load_scene()), empty(far_triangle()) {
    accel = std::make_unique<sst::EmbreeAccel>(scene);
    empty_accel = std::make_unique<sst::EmbreeAccel>(empty);
    lights = std::make_unique<sst::LightSampler>(scene);
    camera = std::make_unique<sst::PinholeCamera>(sst::select_camera(scene, ""), kWidth, kHeight);
    options.width = kWidth;
    options.height = kHeight;
    options.seed = kSeed;
    options.diffuse_only = diffuse_only;
    context = std::make_unique<sst::RenderContext>(
        sst::RenderContext{scene, *accel, *lights, *camera, options, kWidth, kHeight, true});
    empty_context = std::make_unique<sst::RenderContext>(
        sst::RenderContext{scene, *empty_accel, *lights, *camera, options, kWidth, kHeight, true});
    sst::VplParams vp;
    vp.vpls = vpl_count;
    sst::VplStats stats;
    vpls = sst::generate_vpls(scene, *accel, *lights, vp, kSeed, true, &stats);
    clamp_distance = stats.clamp_distance;
    clamp_per_depth = stats.clamp_per_depth;
    view_distance = sst::median_view_distance(*context);
    sst::PathTracerParams direct_only;
    direct_only.max_bounces = 0;
    sst::RayCounters rc;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        sst::PixelSampler sampler = sst::pixel_sampler(kSeed, uint32_t(y * kWidth + x), 0);
        sst::vec2 jitter = sst::pixel_sampler_get2d(sampler);
        sst::Ray ray = camera->generate(float(x) + jitter.x, float(y) + jitter.y);
        sst::Surface hit;
        sst::PathSample d = sst::trace_path(*context, direct_only, ray, sampler, rc, &hit);
        if (!(d.depth > 0.0f)) continue;
        points.push_back(sst::shading_point(hit, ray.direction, d.depth, diffuse_only, x, y));
        samplers.push_back(sampler);
      }
  }

  static sst::Scene load_scene() {
    std::filesystem::path path =
        std::filesystem::path(SST_SHARED_SCENES) / "breakfast-room" / "breakfast-room-point.gltf";
    return std::filesystem::exists(path) ? sst::load_gltf(path.string()) : sst::load_default_scene();
  }
};

const Frame& frame_for(int vpls, bool diffuse_only) {
  static std::map<std::pair<int, bool>, std::unique_ptr<Frame>> frames;
  auto& f = frames[{vpls, diffuse_only}];
  if (!f) f = std::make_unique<Frame>(vpls, diffuse_only);
  return *f;
}

std::unique_ptr<sst::IndirectSampler> make_sampler(const std::string& method) {
  if (method == "slc") return std::make_unique<sst::SlcSampler>(sst::LightTreeParams{});
  return std::make_unique<sst::SstSampler>(sst::LightTreeParams{}, sst::SstParams{});
}

void walk(benchmark::State& state, const std::string& method, bool in_scene, bool diffuse_only = true) {
  const Frame& f = frame_for(int(state.range(0)), diffuse_only);
  std::unique_ptr<sst::IndirectSampler> sampler = make_sampler(method);
  sst::StageTimer timer;
  nlohmann::json counters;
  sampler->prepare({in_scene ? *f.context : *f.empty_context, f.vpls, f.clamp_distance, f.clamp_per_depth,
                    f.view_distance},
                   timer, counters);
  uint64_t nodes = 0, samples = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    auto start = std::chrono::steady_clock::now();
    sst::vec3 sum(0.0f);
    for (size_t i = 0; i < f.points.size(); ++i) {
      sst::PixelSampler ps = f.samplers[i];
      sst::IndirectEstimate e = sampler->estimate(f.points[i], ps);
      sum += e.value;
      nodes += e.nodes_visited;
    }
    benchmark::DoNotOptimize(sum);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    samples += f.points.size();
  }
  state.counters["ns_per_sample"] = 1e9 * seconds / double(samples);
  state.counters["nodes_per_sample"] = double(nodes) / double(samples);
  state.counters["ns_per_step"] = 1e9 * seconds / double(nodes);
}

void BM_TreeWalk(benchmark::State& state, std::string method) { walk(state, method, true); }
void BM_TreeWalkNoScene(benchmark::State& state, std::string method) { walk(state, method, false); }
void BM_TreeWalkNoSceneMaterials(benchmark::State& state, std::string method) { walk(state, method, false, false); }

BENCHMARK_CAPTURE(BM_TreeWalk, slc, std::string("slc"))->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TreeWalk, sst, std::string("sst"))->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TreeWalkNoScene, slc, std::string("slc"))->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TreeWalkNoScene, sst, std::string("sst"))->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TreeWalkNoSceneMaterials, slc, std::string("slc"))->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_TreeWalkNoSceneMaterials, sst, std::string("sst"))->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
