// VPL generation time (instant radiosity light paths) at 10k and 100k VPLs on the built-in
// Cornell box and, when ../shared/scenes is present, the breakfast room. Full-BRDF mode (diffuse
// part of the albedo), default bounces (8, roulette after 3), 2 threads. Only generation is
// timed: loading and the acceleration structure are built once per scene.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>

#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/vpl/vpl_generator.h"

namespace {

struct Prepared {
  sst::Scene scene;
  std::unique_ptr<sst::EmbreeAccel> accel;
  std::unique_ptr<sst::LightSampler> lights;
  explicit Prepared(sst::Scene s) : scene(std::move(s)) {
    accel = std::make_unique<sst::EmbreeAccel>(scene);
    lights = std::make_unique<sst::LightSampler>(scene);
  }
};

void run(benchmark::State& state, const Prepared& p) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  sst::VplParams params;
  params.vpls = int(state.range(0));
  uint64_t rays = 0, paths = 0;
  double seconds = 0.0;
  uint32_t seed = 0;
  for (auto _ : state) {
    sst::VplStats stats;
    sst::VplSet vpls = sst::generate_vpls(p.scene, *p.accel, *p.lights, params, seed++, false, &stats);
    benchmark::DoNotOptimize(vpls.data());
    state.SetIterationTime(stats.ms / 1e3);
    seconds += stats.ms / 1e3;
    rays += stats.rays;
    paths += stats.paths;
  }
  double n = double(state.iterations());
  state.counters["ms"] = 1e3 * seconds / n;
  state.counters["Mrays_per_s"] = double(rays) / seconds / 1e6;
  state.counters["rays_per_vpl"] = double(rays) / (n * double(params.vpls));
  state.counters["vpls_per_path"] = n * double(params.vpls) / double(paths);
}

void BM_VplCornellBox(benchmark::State& state) {
  static Prepared prepared(sst::load_default_scene());
  run(state, prepared);
}

void BM_VplBreakfastRoom(benchmark::State& state) {
  static std::unique_ptr<Prepared> prepared;
  std::filesystem::path path = std::filesystem::path(SST_SHARED_SCENES) / "breakfast-room" / "breakfast-room.gltf";
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("../shared/scenes/breakfast-room not present");
    return;
  }
  if (!prepared) prepared = std::make_unique<Prepared>(sst::load_gltf(path.string()));
  run(state, *prepared);
}

BENCHMARK(BM_VplCornellBox)->Arg(10000)->Arg(100000)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_VplBreakfastRoom)->Arg(10000)->Arg(100000)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace
