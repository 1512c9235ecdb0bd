// Path-tracing throughput: ms per sample per pixel and Mrays/s on the staircase and the breakfast
// room at their reference sizes (180x320 and 320x180, diffuse-only, 8 bounces, 2 threads) and on
// the built-in Cornell box (256x256), the renders the Cycles references were made with (see
// cycles_side_by_side.sh for Cycles). Only the path-tracing pass is timed: loading and the
// acceleration structure are built once. The argument is RenderOptions::path_batch: 0 traces one
// path at a time, 1024 keeps that many paths in flight per thread, their rays in Embree streams.
//
// BM_PathTraceVsEmbree/<scene>/<batch> measures how close the path tracer comes to Embree's own
// rate for the rays it traces: one render at kMixSpp records its rays (camera, bounce,
// light-sample shadow rays, in each thread's order; core/accel/ray_log.h), then every iteration
// renders the same samples again and replays the recorded rays through Embree alone, as the render
// hands them over (one at a time, or runs of one kind as streams), both on 2 threads, one after the
// other. Counters: medians of pt_ms and embree_ms, and of their per-iteration ratio
// embree_share = embree_ms / pt_ms.
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_reduce.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>

#include "core/pipeline/method_registry.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/util/statistics.h"

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

  Prepared(sst::Scene s, int width, int height, int spp = kSpp) : scene(std::move(s)) {
    options.width = width;
    options.height = height;
    options.spp = spp;
    options.diffuse_only = true;
    options.path_batch = 0;
    accel = std::make_unique<sst::EmbreeAccel>(scene);
    lights = std::make_unique<sst::LightSampler>(scene);
    camera = std::make_unique<sst::PinholeCamera>(scene.cameras.front(), width, height);
    method = sst::create_method("pt", {{"max_bounces", 8}});
  }
};

void run(benchmark::State& state, Prepared& p) {
  p.options.path_batch = int(state.range(0));
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

// A scene of ../shared/scenes, or null when it is absent.
std::unique_ptr<Prepared> prepare_shared(const char* folder, const char* file, int width, int height, int spp) {
  std::filesystem::path path = std::filesystem::path(SST_SHARED_SCENES) / folder / file;
  if (!std::filesystem::exists(path)) return nullptr;
  return std::make_unique<Prepared>(sst::load_gltf(path.string()), width, height, spp);
}

void BM_PathTraceStaircase(benchmark::State& state) {
  static std::unique_ptr<Prepared> prepared = prepare_shared("staircase", "staircase.gltf", 180, 320, kSpp);
  if (!prepared) return state.SkipWithError("../shared/scenes/staircase not present");
  run(state, *prepared);
}

void BM_PathTraceBreakfastRoom(benchmark::State& state) {
  static std::unique_ptr<Prepared> prepared = prepare_shared("breakfast-room", "breakfast-room.gltf", 320, 180, kSpp);
  if (!prepared) return state.SkipWithError("../shared/scenes/breakfast-room not present");
  run(state, *prepared);
}

void BM_PathTraceCornellBox(benchmark::State& state) {
  static Prepared prepared(sst::load_default_scene(), 256, 256);
  run(state, prepared);
}

// Samples per pixel of the ray-mix comparison: the recorded rays of the staircase at 4 spp take
// about 72 MB (2M rays of 36 bytes).
constexpr int kMixSpp = 4;

void path_trace_vs_embree(benchmark::State& state, Prepared& p) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  p.options.seed = 0;
  p.options.path_batch = int(state.range(0));
  const sst::RayBatchApi api =
      p.options.path_batch > 0 ? sst::parse_ray_batch_api(p.options.batch_rays) : sst::RayBatchApi::single;
  sst::RenderContext context{p.scene, *p.accel, *p.lights, *p.camera, p.options, p.options.width, p.options.height, true};
  sst::RayLog log;
  {
    p.accel->set_ray_log(&log);
    sst::StageTimer timer;
    p.method->render(context, timer);
    p.accel->set_ray_log(nullptr);
  }
  const std::vector<sst::RecordedRay> rays = log.take();
  const sst::RayMix mix = sst::ray_mix(rays);
  std::vector<double> pt_ms, embree_ms, share;
  for (auto _ : state) {
    sst::StageTimer timer;
    sst::FrameOutput frame = p.method->render(context, timer);
    benchmark::DoNotOptimize(frame.color.data.data());
    const auto start = std::chrono::steady_clock::now();
    size_t hits = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, rays.size(), 4096), size_t(0),
        [&](const tbb::blocked_range<size_t>& r, size_t h) {
          return h + p.accel->replay(rays.data() + r.begin(), r.size(), api);
        },
        std::plus<size_t>());
    benchmark::DoNotOptimize(hits);
    const double replay_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    pt_ms.push_back(timer.ms("render"));
    embree_ms.push_back(replay_ms);
    share.push_back(replay_ms / timer.ms("render"));
    state.SetIterationTime((timer.ms("render") + replay_ms) / 1e3);
  }
  state.counters["pt_ms"] = sst::median(pt_ms);
  state.counters["embree_ms"] = sst::median(embree_ms);
  state.counters["embree_share"] = sst::median(share);
  state.counters["closest_hit_rays"] = double(mix.closest_hit);
  state.counters["occlusion_rays"] = double(mix.occlusion);
  state.counters["embree_Mrays_per_s"] = double(rays.size()) / sst::median(embree_ms) / 1e3;
}

void BM_PathTraceVsEmbreeStaircase(benchmark::State& state) {
  static std::unique_ptr<Prepared> prepared = prepare_shared("staircase", "staircase.gltf", 180, 320, kMixSpp);
  if (!prepared) return state.SkipWithError("../shared/scenes/staircase not present");
  path_trace_vs_embree(state, *prepared);
}

void BM_PathTraceVsEmbreeBreakfastRoom(benchmark::State& state) {
  static std::unique_ptr<Prepared> prepared = prepare_shared("breakfast-room", "breakfast-room.gltf", 320, 180, kMixSpp);
  if (!prepared) return state.SkipWithError("../shared/scenes/breakfast-room not present");
  path_trace_vs_embree(state, *prepared);
}

void BM_PathTraceVsEmbreeCornellBox(benchmark::State& state) {
  static Prepared prepared(sst::load_default_scene(), 256, 256, kMixSpp);
  path_trace_vs_embree(state, prepared);
}

BENCHMARK(BM_PathTraceStaircase)->Arg(0)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(4.0);
BENCHMARK(BM_PathTraceBreakfastRoom)->Arg(0)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(4.0);
BENCHMARK(BM_PathTraceCornellBox)->Arg(0)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(4.0);
BENCHMARK(BM_PathTraceVsEmbreeStaircase)->Arg(0)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(7);
BENCHMARK(BM_PathTraceVsEmbreeBreakfastRoom)->Arg(0)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(7);
BENCHMARK(BM_PathTraceVsEmbreeCornellBox)->Arg(0)->Arg(1024)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(7);

}  // namespace
