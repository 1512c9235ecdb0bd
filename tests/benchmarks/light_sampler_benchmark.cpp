// The light samplers' costs on 2 threads: building the emitter tree over 10k, 100k and 1M
// emissive triangles (LightSampler's whole setup: power distribution, leaves, Morton sort,
// bottom-up merge), and one pick for a shading point with each sampler (power: a binary search
// of the CDF; tree and slc: a walk of log2(n) levels) at 100k emissive triangles. The scene is
// tests/analytic_scenes.h's many_lights: random small emissive triangles in an 8 m room.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <random>

#include "core/lights/light_sampler.h"
#include "tests/analytic_scenes.h"

namespace {

void BM_LightSetup(benchmark::State& state, sst::LightSamplerKind kind) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  sst::Scene scene = sst::test::many_lights(1, int(state.range(0)), 0, 0, false);
  for (auto _ : state) {
    sst::LightSampler lights(scene, kind);
    benchmark::DoNotOptimize(lights.packed().tree.data());
  }
  state.counters["lights"] = double(state.range(0));
}
BENCHMARK_CAPTURE(BM_LightSetup, power, sst::LightSamplerKind::Power)
    ->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_LightSetup, tree, sst::LightSamplerKind::Tree)
    ->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The tree build alone (sort and merge) over leaves made beforehand, as LightSampler makes them.
void BM_EmitterTreeBuild(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  sst::Scene scene = sst::test::many_lights(1, int(state.range(0)), 0, 0, false);
  sst::LightSampler lights(scene, sst::LightSamplerKind::Tree);
  std::vector<sst::glsl::EmitterNode> leaves;
  for (uint32_t e = 0; e < lights.light_count(); ++e) {
    sst::glsl::EmitterNode n = lights.packed().tree[lights.packed().distribution[e].tree_node];
    n.entry = LIGHT_NONE;
    leaves.push_back(n);
  }
  for (auto _ : state) {
    sst::EmitterTree tree = sst::build_emitter_tree(leaves);
    benchmark::DoNotOptimize(tree.nodes.data());
  }
}
BENCHMARK(BM_EmitterTreeBuild)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LightPick(benchmark::State& state, sst::LightSamplerKind kind) {
  static const sst::Scene scene = sst::test::many_lights(2, 100000, 0, 0, false);
  sst::LightSampler lights(scene, kind);
  std::mt19937 rng(3);
  auto uniform = [&]() { return float(rng() >> 8) * 0x1p-24f; };
  std::vector<sst::vec3> points(4096);
  for (sst::vec3& p : points) p = sst::vec3(10 * uniform() - 5, 0.0f, 10 * uniform() - 5);
  size_t i = 0;
  for (auto _ : state) {
    float pmf = 0.0f, u = 0.0f;
    uint32_t e = lights.pick(points[i++ & 4095], sst::vec3(0, 1, 0), uniform(), pmf, u);
    benchmark::DoNotOptimize(e);
    benchmark::DoNotOptimize(pmf);
  }
}
BENCHMARK_CAPTURE(BM_LightPick, power, sst::LightSamplerKind::Power)->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_LightPick, tree, sst::LightSamplerKind::Tree)->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_LightPick, slc, sst::LightSamplerKind::Slc)->Unit(benchmark::kNanosecond);

}  // namespace
