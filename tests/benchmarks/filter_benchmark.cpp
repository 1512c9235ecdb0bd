// The G-buffer-guided filters at 1280x720 (core/filter/filters.h on 2 CPU threads, as the other
// benchmarks; gpu/filter_pass.h on Vulkan device 0, timed by its timestamps) with their default
// parameters, on the analytic two-plane edge with noise and a sky band (the tap count, not the
// content, sets the cost). Five repetitions of one run each; read the median.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <memory>

#include "core/filter/filters.h"
#include "tests/core/filter/filter_test_images.h"
#ifdef SST_HAVE_VULKAN
#include "core/pipeline/backend.h"
#include "gpu/filter_pass.h"
#endif

namespace {

constexpr int kWidth = 1280, kHeight = 720;

struct Inputs {
  sst::test::TwoPlanes full = sst::test::two_planes(kWidth, kHeight, sst::vec3(0.1f), sst::vec3(0.6f), 0.5f, 0.5f, 1, 40);
  sst::Image moments = sst::test::single_frame_moments(full.color);
  sst::Image history = sst::test::constant_image(kWidth, kHeight, 1, 1.0f);
  sst::Image low = sst::test::point_downsample(full.color, 2);
  sst::Image low_depth = sst::test::point_downsample(full.depth, 2);
  sst::Image low_normal = sst::test::point_downsample(full.normal, 2);
};

const Inputs& inputs() {
  static const Inputs in;
  return in;
}

void BM_FilterAtrousCpu(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  const Inputs& in = inputs();
  for (auto _ : state) benchmark::DoNotOptimize(sst::atrous_filter(in.full.color, in.full.depth, in.full.normal, {}));
}

void BM_FilterSvgfCpu(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  const Inputs& in = inputs();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        sst::svgf_spatial(in.full.color, in.moments, in.history, in.full.depth, in.full.normal, {}));
}

void BM_FilterUpsampleCpu(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  const Inputs& in = inputs();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        sst::joint_bilateral_upsample(in.low, in.low_depth, in.low_normal, in.full.depth, in.full.normal, {}));
}

#define SST_FILTER_BENCHMARK(name) BENCHMARK(name)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(5)
SST_FILTER_BENCHMARK(BM_FilterAtrousCpu);
SST_FILTER_BENCHMARK(BM_FilterSvgfCpu);
SST_FILTER_BENCHMARK(BM_FilterUpsampleCpu);

#ifdef SST_HAVE_VULKAN
// The GPU time of the dispatches only (uploads, downloads and pipeline creation excluded).
template <class Run>
void run_gpu(benchmark::State& state, const Run& run) {
  std::string reason;
  if (sst::list_vulkan_devices(&reason).empty()) {
    state.SkipWithError(("no Vulkan device: " + reason).c_str());
    return;
  }
  static sst::gpu::VulkanContext context(0);
  state.SetLabel(context.info().name);
  for (auto _ : state) state.SetIterationTime(run(context) / 1e3);
}

void BM_FilterAtrousGpu(benchmark::State& state) {
  const Inputs& in = inputs();
  run_gpu(state, [&](const sst::gpu::VulkanContext& c) {
    return sst::gpu::atrous_filter(c, in.full.color, in.full.depth, in.full.normal, {}).gpu_ms;
  });
}

void BM_FilterSvgfGpu(benchmark::State& state) {
  const Inputs& in = inputs();
  run_gpu(state, [&](const sst::gpu::VulkanContext& c) {
    return sst::gpu::svgf_spatial(c, in.full.color, in.moments, in.history, in.full.depth, in.full.normal, {}).gpu_ms;
  });
}

void BM_FilterUpsampleGpu(benchmark::State& state) {
  const Inputs& in = inputs();
  run_gpu(state, [&](const sst::gpu::VulkanContext& c) {
    return sst::gpu::joint_bilateral_upsample(c, in.low, in.low_depth, in.low_normal, in.full.depth, in.full.normal, {})
        .gpu_ms;
  });
}

SST_FILTER_BENCHMARK(BM_FilterAtrousGpu)->UseManualTime();
SST_FILTER_BENCHMARK(BM_FilterSvgfGpu)->UseManualTime();
SST_FILTER_BENCHMARK(BM_FilterUpsampleGpu)->UseManualTime();
#endif

}  // namespace
