// Light-tree build stages at 10k, 100k and 1M VPLs on 2 threads: sort keys, radix sort, the radix
// tree found and SST-merged bottom-up, and whole builds (radix and perfect) through a reused
// LightTreeBuilder, as a renderer rebuilding every frame would run them. The target:
// a whole radix SST build of 100k VPLs in at most 2 ms on 2 cores (the SST paper: 0.9 ms on an
// RTX 2080 Ti).
//
// VPLs are generated here, deterministically: `random` = positions uniform in a 10 m cube with
// uniformly random normals and intensities; `room` = on the six walls of a 10 m room, normals
// inward (planar clusters, where substitutes become suitable). Each stage is timed alone
// (manual time) on inputs prepared outside the timed region. SST_BENCH_THREADS=1 runs on one
// thread instead of 2.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <map>

#include "core/lighttree/light_tree.h"
#include "core/lighttree/sort_key.h"
#include "core/lighttree/tree_builders.h"
#include "core/rng/hash_rng.h"

namespace {

using sst::vec3;

sst::VplSet make_vpls(size_t n, bool room) {
  sst::VplSet vpls(n);
  for (size_t i = 0; i < n; ++i) {
    sst::HashRng rng = sst::hash_rng(7, uint32_t(i), 0);
    vec3 p(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng));
    vec3 normal;
    if (room) {
      int face = int(i % 6), axis = face / 2;
      p[axis] = face % 2 ? 1.0f : 0.0f;
      normal = vec3(0.0f);
      normal[axis] = face % 2 ? -1.0f : 1.0f;
    } else {
      float z = 2.0f * hash_rng_next(rng) - 1.0f, phi = 2.0f * sst::kPi * hash_rng_next(rng);
      float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      normal = vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
    vpls[i] = {10.0f * p, normal, vec3(hash_rng_next(rng), hash_rng_next(rng), hash_rng_next(rng))};
  }
  return vpls;
}

const sst::VplSet& vpls_for(size_t n, bool room = false) {
  static std::map<std::pair<size_t, bool>, sst::VplSet> cache;
  auto& v = cache[{n, room}];
  if (v.empty()) v = make_vpls(n, room);
  return v;
}

// 2, or SST_BENCH_THREADS (1 separates the work from the parallel overhead).
size_t thread_count() {
  const char* env = std::getenv("SST_BENCH_THREADS");
  return env ? size_t(std::max(1, std::atoi(env))) : 2;
}

template <class F>
double seconds(F&& f) {
  auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The stages below run on the scratch of one builder, prepared up to the stage under test.
struct Stages {
  const sst::VplSet& vpls;
  sst::Bounds3 bounds;
  sst::LightTreeBuilder::Scratch scratch;
  sst::LightTree tree;
  sst::SubstituteThresholds thresholds;
  explicit Stages(const sst::VplSet& v) : vpls(v), bounds(sst::compute_vpl_bounds(v)) {
    thresholds = {0.5f, 0.005f * bounds.diagonal()};
  }
  void sort() {
    sst::LightTreeBuildStats unused;
    sst::sort_vpls(vpls, bounds, scratch, tree, unused);
  }
};

void BM_SortKeys(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, thread_count());
  Stages s(vpls_for(size_t(state.range(0))));
  for (auto _ : state)
    state.SetIterationTime(seconds([&] {
      sst::Bounds3 b = sst::compute_vpl_bounds(s.vpls);
      sst::compute_sort_keys(s.vpls, b, s.tree.leaf_keys);
    }));
}

void BM_RadixSort(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, thread_count());
  Stages s(vpls_for(size_t(state.range(0))));
  std::vector<uint64_t> keys;
  sst::compute_sort_keys(s.vpls, s.bounds, keys);
  for (auto _ : state) {
    s.tree.leaf_keys = keys;
    state.SetIterationTime(seconds([&] { sst::radix_sort_keys(s.tree.leaf_keys, s.scratch.sort, sst::kIdBits, 64); }));
  }
}

// The radix tree's topology and merge, one bottom-up pass (build_radix_tree).
void BM_RadixTree(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, thread_count());
  Stages s(vpls_for(size_t(state.range(0))));
  s.sort();
  sst::build_radix_tree(s.vpls, s.thresholds, /*store_leaves=*/true, s.scratch, s.tree);  // the tree's storage, as in later frames
  for (auto _ : state)
    state.SetIterationTime(seconds([&] { sst::build_radix_tree(s.vpls, s.thresholds, /*store_leaves=*/true, s.scratch, s.tree); }));
}

void whole_build(benchmark::State& state, const std::string& kind, bool room, const std::string& leaves = "stored") {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, thread_count());
  const sst::VplSet& vpls = vpls_for(size_t(state.range(0)), room);
  sst::LightTreeParams params;
  params.tree = kind;
  params.leaves = leaves;
  sst::LightTreeBuilder builder;
  sst::LightTree tree;
  sst::LightTreeBuildStats stats, sum;
  // Frames after the first: the builder and the tree keep their storage. A first build also
  // faults in its memory (a single frame's tree_build in sst-render's timings).
  builder.build(vpls, params, nullptr, tree, &stats);
  for (auto _ : state) {
    state.SetIterationTime(seconds([&] { builder.build(vpls, params, nullptr, tree, &stats); }));
    sum.bounds_ms += stats.bounds_ms;
    sum.keys_ms += stats.keys_ms;
    sum.sort_ms += stats.sort_ms;
    sum.hierarchy_ms += stats.hierarchy_ms;
    sum.merge_ms += stats.merge_ms;
  }
  double n = double(state.iterations());
  state.counters["bounds_ms"] = sum.bounds_ms / n;
  state.counters["keys_ms"] = sum.keys_ms / n;
  state.counters["sort_ms"] = sum.sort_ms / n;
  state.counters["hierarchy_ms"] = sum.hierarchy_ms / n;
  state.counters["merge_ms"] = sum.merge_ms / n;
}

// BM_RadixBuild stores the leaves, as every build did before made leaves became the default
// (BM_RadixBuildMadeLeaves), so that its figures compare across the change.
void BM_RadixBuild(benchmark::State& state) { whole_build(state, "radix", false); }
void BM_RadixBuildRoom(benchmark::State& state) { whole_build(state, "radix", true); }
void BM_RadixBuildMadeLeaves(benchmark::State& state) { whole_build(state, "radix", false, "made"); }
void BM_PerfectBuild(benchmark::State& state) { whole_build(state, "perfect", false); }

#define SST_TREE_BENCH(f) \
  BENCHMARK(f)->Arg(10000)->Arg(100000)->Arg(1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(1.0)

SST_TREE_BENCH(BM_SortKeys);
SST_TREE_BENCH(BM_RadixSort);
SST_TREE_BENCH(BM_RadixTree);
SST_TREE_BENCH(BM_RadixBuild);
SST_TREE_BENCH(BM_RadixBuildRoom);
SST_TREE_BENCH(BM_RadixBuildMadeLeaves);
SST_TREE_BENCH(BM_PerfectBuild);

}  // namespace
