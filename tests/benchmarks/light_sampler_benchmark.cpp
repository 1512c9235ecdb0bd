// The light samplers' costs: building the emitter tree over 1k to 1M emissive triangles
// (LightSampler's whole setup on 2 threads: power distribution, leaves, the tree; the tree alone
// with each build, saoh and morton, on 1 and 2 threads), and one pick for a shading point with
// each sampler (power: a binary search of the CDF; tree and slc: a walk down the tree, with each
// build) at 100k emissive triangles. The scene is tests/analytic_scenes.h's many_lights: random
// small emissive triangles in an 8 m room.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
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

// The tree build alone over leaves made beforehand, as LightSampler makes them; arguments: the
// number of lights, the threads. Counters: the tree's bytes and its deepest leaf.
void BM_EmitterTreeBuild(benchmark::State& state, sst::EmitterTreeBuild build) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(state.range(1)));
  sst::Scene scene = sst::test::many_lights(1, int(state.range(0)), 0, 0, false);
  sst::LightSampler lights(scene, sst::LightSamplerKind::Tree);
  std::vector<sst::glsl::EmitterNode> leaves;
  for (uint32_t e = 0; e < lights.light_count(); ++e) {
    sst::glsl::EmitterNode n = lights.packed().tree[lights.packed().distribution[e].tree_node];
    n.entry = LIGHT_NONE;
    n.parent = 0u;
    leaves.push_back(n);
  }
  size_t bytes = 0;
  uint32_t deepest = 0;
  for (auto _ : state) {
    sst::EmitterTree tree = sst::build_emitter_tree(leaves, build);
    benchmark::DoNotOptimize(tree.nodes.data());
    state.PauseTiming();
    bytes = tree.nodes.size() * sizeof(sst::glsl::EmitterNode);
    for (uint32_t node : tree.node_of_entry) {
      uint32_t depth = 0;
      for (; node > 1u; node = tree.nodes[node].parent) ++depth;
      deepest = std::max(deepest, depth);
    }
    state.ResumeTiming();
  }
  state.counters["bytes"] = double(bytes);
  state.counters["depth"] = double(deepest);
}
BENCHMARK_CAPTURE(BM_EmitterTreeBuild, saoh, sst::EmitterTreeBuild::Saoh)
    ->ArgsProduct({{1000, 100000, 1000000}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_EmitterTreeBuild, morton, sst::EmitterTreeBuild::Morton)
    ->ArgsProduct({{1000, 100000, 1000000}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_LightPick(benchmark::State& state, sst::LightSamplerKind kind, sst::EmitterTreeBuild build) {
  static const sst::Scene scene = sst::test::many_lights(2, 100000, 0, 0, false);
  sst::LightSampler lights(scene, kind, build);
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
BENCHMARK_CAPTURE(BM_LightPick, power, sst::LightSamplerKind::Power, sst::EmitterTreeBuild::Saoh)
    ->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_LightPick, tree_saoh, sst::LightSamplerKind::Tree, sst::EmitterTreeBuild::Saoh)
    ->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_LightPick, tree_morton, sst::LightSamplerKind::Tree, sst::EmitterTreeBuild::Morton)
    ->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_LightPick, slc_saoh, sst::LightSamplerKind::Slc, sst::EmitterTreeBuild::Saoh)
    ->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_LightPick, slc_morton, sst::LightSamplerKind::Slc, sst::EmitterTreeBuild::Morton)
    ->Unit(benchmark::kNanosecond);

}  // namespace
