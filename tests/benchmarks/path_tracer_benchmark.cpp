// Path-tracing throughput: ms per sample per pixel and Mrays/s on the staircase at its reference
// size (180x320, diffuse-only, 8 bounces, 2 threads) and on the built-in Cornell box (256x256),
// the renders the Cycles references were made with (see cycles_side_by_side.sh for Cycles).
// Only the path-tracing pass is timed: loading and the acceleration structure are built once.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>

#include "core/pipeline/method_registry.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"

namespace {

// Samples per pixel of one timed render: a pixel's samples run back to back, as in any render
// of more than one spp, so the figure is what a user's render costs per spp.
constexpr int kSpp = 16;

struct Prepared {
  sst::Scene scene;
  sst::RenderOptions options;
  std::unique_ptr<sst::EmbreeAccel> accel;
  std::unique_ptr<sst::LightSampler> lights;
  std::unique_ptr<sst::PinholeCamera> camera;
  std::unique_ptr<sst::Method> method;

  Prepared(sst::Scene s, int width, int height) : scene(std::move(s)) {
    options.width = width;
    options.height = height;
    options.spp = kSpp;
    options.diffuse_only = true;
    accel = std::make_unique<sst::EmbreeAccel>(scene);
    lights = std::make_unique<sst::LightSampler>(scene);
    camera = std::make_unique<sst::PinholeCamera>(scene.cameras.front(), width, height);
    method = sst::create_method("pt", {{"max_bounces", 8}});
  }
};

void run(benchmark::State& state, Prepared& p) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  sst::RenderContext context{p.scene, *p.accel, *p.lights, *p.camera, p.options, p.options.width, p.options.height, true};
  uint64_t rays = 0;
  double seconds = 0.0;
  uint32_t seed = 0;
  for (auto _ : state) {
    p.options.seed = seed++;  // new samples each iteration
    sst::StageTimer timer;
    sst::FrameOutput frame = p.method->render(context, timer);
    state.SetIterationTime(timer.ms("render") / 1e3);
    seconds += timer.ms("render") / 1e3;
    rays += frame.counters.total_rays();
    benchmark::DoNotOptimize(frame.color.data.data());
  }
  state.counters["ms_per_spp"] = 1e3 * seconds / double(state.iterations() * kSpp);
  state.counters["Mrays_per_s"] = double(rays) / seconds / 1e6;
}

void BM_PathTraceStaircase(benchmark::State& state) {
  static std::unique_ptr<Prepared> prepared;
  std::filesystem::path path = std::filesystem::path(SST_SHARED_SCENES) / "staircase" / "staircase.gltf";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("../shared/scenes/staircase not present");
    return;
  }
  if (!prepared) prepared = std::make_unique<Prepared>(sst::load_gltf(path.string()), 180, 320);
  run(state, *prepared);
}

void BM_PathTraceCornellBox(benchmark::State& state) {
  static Prepared prepared(sst::load_default_scene(), 256, 256);
  run(state, prepared);
}

BENCHMARK(BM_PathTraceStaircase)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(4.0);
BENCHMARK(BM_PathTraceCornellBox)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(4.0);

}  // namespace
