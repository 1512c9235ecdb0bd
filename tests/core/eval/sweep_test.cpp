// In-process sweeps of tiny renders of the built-in Cornell box: files, references and their
// cache, resume, equal-time calibration bounds, and the metrics check catching a broken method.
#include "core/eval/sweep.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include "core/eval/merge.h"
#include "core/eval/metrics_check.h"
#include "core/eval/run_executor.h"
#include "core/eval/sequence_checkpoint.h"
#include "core/image/image.h"
#include "core/manylight/exhaustive/exhaustive_sampler.h"
#include "core/manylight/many_light_method.h"
#include "core/manylight/slc/slc_sampler.h"
#include "core/pipeline/method_registry.h"
#include "core/scene/default_scene.h"
#include "core/util/error.h"
#include "core/util/json_io.h"
#include "tests/core/eval/eval_test_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

using nlohmann::json;

ExperimentConfig tiny_config(json extra = json::object()) {
  json j = {{"width", 24}, {"height", 24}, {"spp", 2}, {"vpls", 300}, {"reference", {{"spp", 16}}}};
  j.update(extra);
  ExperimentConfig c = parse_experiment_config(j, "tiny");
  c.name = "tiny";
  return c;
}

SweepOptions options_in(const fs::path& dir) {
  SweepOptions o;
  o.output_dir = (dir / "out").string();
  o.cache_dir = (dir / "cache").string();
  o.quiet = true;
  return o;
}

using test::without_timings;

TEST(Sweep, WritesEveryRunAndReusesCachedReferences) {
  auto dir = test::temp_dir();
  ExperimentConfig config = tiny_config({{"axes", {{"method", {"slc", "sst"}}}}, {"seeds", 2}});
  json r = run_sweep(config, options_in(dir));
  ASSERT_EQ(r["runs"].size(), 4u);
  ASSERT_EQ(r["groups"].size(), 2u);
  ASSERT_EQ(r["references"].size(), 1u);  // one path reference shared by all runs
  for (const json& run : r["runs"]) {
    for (const auto& [kind, path] : run["images"].items()) EXPECT_TRUE(fs::exists(dir / "out" / path.get<std::string>()));
    EXPECT_GT(run["metrics"]["rmse"].get<double>(), 0.0);
  }
  EXPECT_TRUE(r["groups"][0]["bias2"].is_number());
  for (const char* f : {"results.json", "results.csv", "report.html", "config.json"}) EXPECT_TRUE(fs::exists(dir / "out" / f));
  std::string ref_id = r["references"].begin().key();
  auto cached = dir / "cache" / (ref_id + ".json");
  ASSERT_TRUE(fs::exists(cached));
  auto stamp = fs::last_write_time(cached);
  SweepOptions other = options_in(dir);
  other.output_dir = (dir / "out2").string();
  json again = run_sweep(config, other);
  EXPECT_EQ(fs::last_write_time(cached), stamp);  // not rendered again
  EXPECT_EQ(without_timings(again)["runs"], without_timings(r)["runs"]);
}

TEST(Sweep, VplReferenceUsesTheRunsOwnVplSet) {
  auto dir = test::temp_dir();
  // exhaustive at the reference's spp and seed is the reference itself: zero error, exactly.
  ExperimentConfig config = tiny_config({{"method", "exhaustive"}, {"spp", 4}, {"reference", {{"kind", "vpl"}, {"spp", 4}}},
                                         {"seeds", 2}});
  json r = run_sweep(config, options_in(dir));
  ASSERT_EQ(r["references"].size(), 2u);  // one per seed: each seed draws its own VPLs
  for (const json& run : r["runs"]) EXPECT_EQ(run["metrics"]["rmse"].get<double>(), 0.0);
}

TEST(Sweep, MetricsLayerDirectMeasuresTheDirectLightAlone) {
  // pt with two bounces against a direct-light reference: its colour carries the indirect light
  // too, its direct layer the direct light alone. Image means (green), whose noise at 8 spp is a
  // few percent: the RMSE of so few samples is mostly noise either way.
  struct Measured {
    double mean, reference_mean;
    std::string hash;
  };
  auto measure = [](const std::string& layer) {
    auto dir = test::temp_dir();
    json extra = {{"method", "pt"}, {"max_bounces", 2}, {"spp", 8}, {"reference", {{"spp", 64}, {"max_bounces", 0}}}};
    if (!layer.empty()) extra["metrics_layer"] = layer;
    json r = run_sweep(tiny_config(extra), options_in(dir));
    const json& run = r["runs"][0];
    EXPECT_EQ(run.value("metrics_layer", std::string("color")), layer.empty() ? "color" : layer);
    return Measured{run["metrics"]["mean_test"][1].get<double>(), run["metrics"]["mean_reference"][1].get<double>(),
                    run["spec_hash"].get<std::string>()};
  };
  Measured color = measure(""), direct = measure("direct");
  std::cout << "green means against the direct-light reference's " << direct.reference_mean << ": color "
            << color.mean << ", direct layer " << direct.mean << "\n";
  EXPECT_NEAR(direct.mean / direct.reference_mean, 1.0, 0.1);
  EXPECT_GT(color.mean / color.reference_mean, 1.2);
  EXPECT_NE(direct.hash, color.hash);
}

TEST(Sweep, RefusesToOverwriteAndResumesOnlyWhatIsMissing) {
  auto dir = test::temp_dir();
  ExperimentConfig config = tiny_config({{"axes", {{"method", {"slc", "pt"}}}}});
  SweepOptions o = options_in(dir);
  json first = run_sweep(config, o);
  EXPECT_THROW(run_sweep(config, o), Error);
  auto kept = dir / "out/runs/0000-slc/run.json";
  auto stamp = fs::last_write_time(kept);
  fs::remove(dir / "out/runs/0001-pt/run.json");  // as if killed before this run finished
  o.resume = true;
  json resumed = run_sweep(config, o);
  EXPECT_EQ(fs::last_write_time(kept), stamp);
  EXPECT_TRUE(fs::exists(dir / "out/runs/0001-pt/run.json"));
  EXPECT_EQ(without_timings(resumed), without_timings(first));
}

TEST(Sweep, ShardsAreDisjointAndMergeToTheWholeSweep) {
  auto dir = test::temp_dir();
  ExperimentConfig config = tiny_config({{"axes", {{"method", {"slc", "pt", "sst"}}}}});
  json whole = run_sweep(config, options_in(dir / "whole"));
  for (int i = 0; i < 2; ++i) {
    SweepOptions o = options_in(dir);
    o.output_dir = (dir / ("shard" + std::to_string(i))).string();
    o.shard_index = i;
    o.shard_count = 2;
    EXPECT_EQ(run_sweep(config, o)["runs"].size(), i == 0 ? 2u : 1u);
  }
  EXPECT_THROW(merge_sweep({(dir / "shard0").string()}, (dir / "merged").string()), Error);  // a shard missing
  json merged = merge_sweep({(dir / "shard0").string(), (dir / "shard1").string()}, (dir / "merged").string());
  EXPECT_EQ(without_timings(merged), without_timings(whole));
  EXPECT_TRUE(fs::exists(dir / "merged/runs/0001-pt/image.png"));
}

TEST(Sweep, ShardSyntax) {
  int i = 0, n = 0;
  parse_shard("2/5", i, n);
  EXPECT_EQ(i, 2);
  EXPECT_EQ(n, 5);
  EXPECT_THROW(parse_shard("5/5", i, n), Error);
  EXPECT_THROW(parse_shard("1", i, n), Error);
  EXPECT_THROW(parse_shard("1/2x", i, n), Error);
}

// A sequence run interrupted after some frames continues from its checkpoint at the next frame,
// with the numbers and image of the run that was never interrupted.
TEST(Sweep, AnInterruptedSequenceRunResumesAtItsNextFrame) {
  fs::path dir = test::temp_dir();
  const std::string cut_dir = (dir / "cut").string();
  const RunSpec run =
      test::tiny_sequence_run({{"method", "sst"}, {"vpls", 300}, {"spp", 1}, {"temporal", true}, {"denoise", "svgf"}});
  const json whole = test::expect_resumes(run, (dir / "whole").string(), cut_dir);

  // A checkpoint of another spec is not continued: the run starts over and says why.
  Scene scene = load_default_scene();
  test::InterruptingReferences references;
  references.interrupt_at = 3;
  EXPECT_THROW(execute_run(scene, run, {}, references.function(), cut_dir), Error);
  references.interrupt_at = -1;
  references.calls = 0;
  RunSpec changed = run;
  changed.spec_hash = "another";
  json restarted = execute_run(scene, changed, {}, references.function(), cut_dir);
  EXPECT_EQ(references.calls, 4);
  EXPECT_NE(restarted["warnings"].dump().find("checkpoint discarded"), std::string::npos) << restarted["warnings"];
  EXPECT_EQ(restarted["metrics"], whole["metrics"]);
}

// The state methods keep from frame to frame is in the checkpoint: runs with ReSTIR DI's temporal
// reuse, with restir_gi and with gi10 resume with the numbers of the uninterrupted run.
TEST(Sweep, SequenceRunsOfMethodsWithStateResume) {
  for (const json& fields : {json{{"method", "pt"}, {"max_bounces", 1}, {"spp", 1}, {"direct_sampler", "restir"}},
                             json{{"method", "restir_gi"}, {"max_bounces", 2}, {"spp", 1}},
                             json{{"method", "gi10"}, {"cache_warmup_frames", 2}, {"spp", 1}}}) {
    SCOPED_TRACE(fields.dump());
    fs::path dir = test::temp_dir();
    test::expect_resumes(test::tiny_sequence_run(fields), (dir / "whole").string(), (dir / "cut").string());
  }
}

TEST(Sweep, CalibratedSppIsClampedToItsRange) {
  Scene scene = load_default_scene();
  RunSpec run = expand_runs(tiny_config({{"method", "slc"}})).front();
  json probes;
  EXPECT_EQ(calibrate_spp(scene, run, 1e-9, &probes), 1);
  EXPECT_EQ(probes["spp"], json({1, 4}));
  EXPECT_EQ(calibrate_spp(scene, run, 1e12, nullptr), 1 << 16);
}

// SLC with its child probabilities swapped in the walk but not in the estimate's division: the
// kind of slip a refactoring makes. The CI metrics check must catch it.
class SwappedWeightsSlc final : public TreeSamplerBase {
 public:
  using TreeSamplerBase::TreeSamplerBase;
  IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const override {
    IndirectEstimate e;
    uint32_t i = tree_.root;
    double p = 1.0;
    while (!tree_[i].is_leaf()) {
      vec2 w = slc_child_weights(tree_[tree_[i].left], tree_[tree_[i].right], point.p, point.basis, 0.0f);
      double sum = double(w.x) + double(w.y);
      if (!(sum > 0.0)) return e;
      bool left = pixel_sampler_get1d(sampler) < w.y / sum;  // the bug: the sibling's probability
      p *= (left ? w.x : w.y) / sum;
      i = left ? tree_[i].left : tree_[i].right;
    }
    uint32_t vpl = tree_[i].vpl();
    if (vpl < inputs().vpls.size())
      e.value = divide_by_probability(shade_vpl(inputs(), point, inputs().vpls[vpl], e.shadow_rays), tree_probability(float(p)));
    return e;
  }

 protected:
  uint32_t method_id() const override { return ML_METHOD_slc; }
};

TEST(Sweep, MetricsCheckPassesOnCleanCodeAndFailsOnSwappedWeights) {
  auto dir = test::temp_dir();
  ExperimentConfig config = tiny_config({{"width", 48}, {"height", 48}, {"spp", 8}, {"vpls", 2000}, {"seeds", 3},
                                         {"axes", {{"method", {"slc", "sst"}}}}, {"reference", {{"spp", 256}}}});
  json baseline = run_sweep(config, options_in(dir / "baseline"));
  json clean = run_sweep(config, options_in(dir / "clean"));
  EXPECT_TRUE(check_against_baseline(clean, baseline).passed);

  MethodInfo broken = find_method("slc");
  broken.create = [](const json& j) -> std::unique_ptr<Method> {
    SlcParams p;
    params_from_json(p, j, "slc");
    return std::make_unique<ManyLightMethod>(p.vpl, params_to_json(p), std::make_unique<SwappedWeightsSlc>(p.tree));
  };
  ScopedMethodOverride override_slc(broken);
  json bad = run_sweep(config, options_in(dir / "broken"));
  CheckOutcome outcome = check_against_baseline(bad, baseline);
  EXPECT_FALSE(outcome.passed) << outcome.table;
  std::cout << outcome.table;  // what moved, for the log
  EXPECT_NE(outcome.table.find("| slc | rmse |"), std::string::npos);
  EXPECT_EQ(outcome.table.find("| sst | rmse | ") == std::string::npos, false);
}

}  // namespace
}  // namespace sst
