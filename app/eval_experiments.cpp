#include "app/eval_experiments.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "core/eval/distribution_check.h"
#include "core/eval/experiment_config.h"
#include "core/eval/merge.h"
#include "core/eval/metrics_check.h"
#include "core/eval/report.h"
#include "core/eval/sweep.h"
#include "core/eval/table.h"
#include "core/util/error.h"
#include "core/util/json_io.h"

namespace fs = std::filesystem;

namespace sst::app {
namespace {

void add_scene_options(CLI::App* cmd, std::vector<std::string>& scene_dirs, std::string& cache_dir) {
  cmd->add_option("--scene-dir", scene_dirs, "directory to search for scenes (repeatable; also SST_SCENE_PATH)");
  cmd->add_option("--cache-dir", cache_dir, "reference cache [SST_CACHE_DIR or ~/.cache/sst/references]");
}

// The table goes to stdout, so that a sweep piped into a file keeps it; where the files are, to
// stderr with the progress.
void print_summary(const nlohmann::json& results, const std::string& dir) {
  std::fputs(format_table(results, "markdown", {}).c_str(), stdout);
  std::fflush(stdout);
  std::fprintf(stderr, "%zu runs -> %s/results.json, results.csv; open %s\n", results["runs"].size(), dir.c_str(),
               (fs::path(dir) / "report.html").string().c_str());
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepArgs& a) {
  CLI::App* cmd = app.add_subcommand("sweep", "render every run of an experiment config and measure it");
  cmd->add_option("config", a.config, "experiment config (configs/*.json)")->required();
  cmd->add_option("-o,--output", a.output, "results folder [results/<config name>]");
  cmd->add_flag("--resume", a.resume, "keep the finished runs in the results folder and render the rest");
  cmd->add_option("--shard", a.shard, "render only slice i of n (i/n, 0-based); default from SLURM_ARRAY_TASK_*");
  add_scene_options(cmd, a.scene_dirs, a.cache_dir);
  cmd->add_flag("-q,--quiet", a.quiet, "no progress on stderr");
  return cmd;
}

int run_sweep_command(const SweepArgs& a) {
  ExperimentConfig config = load_experiment_config(a.config);
  SweepOptions o;
  o.output_dir = a.output.empty() ? (fs::path("results") / config.name).string() : a.output;
  o.resume = a.resume;
  if (!a.shard.empty()) parse_shard(a.shard, o.shard_index, o.shard_count);
  else shard_from_slurm(o.shard_index, o.shard_count);
  o.scene_dirs = a.scene_dirs;
  o.cache_dir = a.cache_dir;
  o.quiet = a.quiet;
  nlohmann::json results = run_sweep(config, o);
  if (!a.quiet) {
    if (o.shard_count > 1)
      std::fprintf(stderr, "shard %d/%d: %zu runs -> %s/shards/; join the shards with sst-eval merge\n", o.shard_index,
                   o.shard_count, results["runs"].size(), o.output_dir.c_str());
    else
      print_summary(results, o.output_dir);
  }
  return 0;
}

CLI::App* add_merge_command(CLI::App& app, MergeArgs& a) {
  CLI::App* cmd = app.add_subcommand("merge", "join the results folders of a sweep's shards into one");
  cmd->add_option("shards", a.shard_dirs, "results folders written by sweep --shard")->required();
  cmd->add_option("-o,--output", a.output, "merged results folder [the first shard folder]");
  return cmd;
}

int run_merge_command(const MergeArgs& a) {
  std::string out = a.output.empty() ? a.shard_dirs.front() : a.output;
  print_summary(merge_sweep(a.shard_dirs, out), out);
  return 0;
}

CLI::App* add_table_command(CLI::App& app, TableArgs& a) {
  CLI::App* cmd = app.add_subcommand("table", "print the results of a sweep as a table like the papers'");
  cmd->add_option("results", a.results, "results.json (or its folder)")->required();
  cmd->add_option("--format", a.format, "markdown or csv")->capture_default_str();
  cmd->add_option("--stage", a.stages, "add a column with this stage's median time (repeatable)");
  return cmd;
}

int run_table_command(const TableArgs& a) {
  std::string path = fs::is_directory(a.results) ? (fs::path(a.results) / "results.json").string() : a.results;
  std::fputs(format_table(read_json_file(path), a.format, a.stages).c_str(), stdout);
  return 0;
}

CLI::App* add_report_command(CLI::App& app, ReportArgs& a) {
  CLI::App* cmd = app.add_subcommand("report", "write report.html again from a results folder's results.json");
  cmd->add_option("results", a.results, "results folder (or its results.json)")->required();
  return cmd;
}

int run_report_command(const ReportArgs& a) {
  fs::path dir = fs::is_directory(a.results) ? fs::path(a.results) : fs::path(a.results).parent_path();
  write_report(read_json_file((dir / "results.json").string()), dir.string());
  std::fprintf(stderr, "%s\n", (dir / "report.html").string().c_str());
  return 0;
}

CLI::App* add_check_command(CLI::App& app, CheckArgs& a) {
  CLI::App* cmd = app.add_subcommand("check", "re-render a config and fail if its results moved from the baseline's beyond their noise");
  cmd->add_option("config", a.config, "experiment config (configs/ci.json)")->required();
  cmd->add_option("--baseline", a.baseline, "baseline results folder (results/ci)")->required();
  cmd->add_option("-o,--output", a.output, "where the fresh results and check.json go; its runs/ are replaced [<tmp>/sst-check-<name>]");
  cmd->add_flag("--update", a.update, "render and write the results and their statistics as the new baseline instead of checking");
  cmd->add_option("--sigmas", a.sigmas, "median table: tolerance in standard errors of the baseline's noise")->capture_default_str();
  cmd->add_option("--min-relative", a.min_relative, "median table: tolerance floor, fraction of the baseline value")->capture_default_str();
  cmd->add_option("--alpha", a.distribution.alpha, "distribution tests: probability that clean code fails (all groups together)")
      ->capture_default_str()->check(CLI::Range(1e-12, 0.5));
  cmd->add_option("--block", a.distribution.block, "distribution tests: block side in pixels (--update only)")
      ->capture_default_str()->check(CLI::Range(1, 4096));
  cmd->add_option("--seeds", a.seeds, "seeds per group instead of the config's (a power study's fresh sets)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--seed", a.seed, "first seed instead of the config's")->check(CLI::Range(int64_t(0), int64_t(4294967295)));
  cmd->add_option("--statistics-seeds", a.statistics_seeds, "--update: seeds per group of the distribution statistics")
      ->capture_default_str()->check(CLI::Range(2, 10000));
  cmd->add_option("--statistics-seed", a.statistics_seed, "--update: their first seed (keep them disjoint from the check's)")
      ->capture_default_str()->check(CLI::Range(int64_t(0), int64_t(4294967295)));
  cmd->add_flag("--resume", a.resume, "keep finished runs in the output folder instead of rendering them again");
  cmd->add_option("--inject-bias", a.distribution.inject_bias, "fault for measuring power: fresh colour += this x its indirect layer")
      ->check(CLI::Range(-1.0, 10.0));
  cmd->add_option("--inject-variance", a.distribution.inject_variance,
                  "fault for measuring power: noise of this x the baseline's per-pixel variance added to fresh colour")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--same-seed-margin", a.distribution.same_seed_margin,
                  "same-seed tests: relative change of a seed's render below which it counts as none")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--inject-method", a.distribution.inject_method, "inject faults only into groups of this method [all]");
  add_scene_options(cmd, a.scene_dirs, a.cache_dir);
  cmd->add_flag("-q,--quiet", a.quiet, "no progress on stderr");
  return cmd;
}

int run_check_command(const CheckArgs& a) {
  ExperimentConfig config = load_experiment_config(a.config);
  if (a.seeds > 0) config.seeds = a.seeds;
  if (a.seed >= 0) config.base["seed"] = a.seed;
  SweepOptions o;
  o.output_dir = a.update ? a.baseline
                          : (a.output.empty() ? (fs::temp_directory_path() / ("sst-check-" + config.name)).string() : a.output);
  if (!a.resume) fs::remove_all(fs::path(o.output_dir) / "runs");  // a check renders afresh
  o.resume = a.resume;
  o.scene_dirs = a.scene_dirs;
  o.cache_dir = a.cache_dir;
  o.quiet = a.quiet;
  const fs::path statistics_path = fs::path(a.baseline) / "check_statistics.json";
  nlohmann::json baseline, statistics;
  if (!a.update) {  // read before rendering: a missing baseline is an error at once
    baseline = read_json_file((fs::path(a.baseline) / "results.json").string());
    if (fs::exists(statistics_path)) statistics = read_json_file(statistics_path.string());
  }
  nlohmann::json fresh = run_sweep(config, o);
  if (a.update) {
    // The medians table compares a check with the baseline's runs of the same seeds (results.json);
    // the distribution tests need many other seeds, rendered apart and reduced to statistics.
    ExperimentConfig many = config;
    many.seeds = a.statistics_seeds;
    many.base["seed"] = a.statistics_seed;
    SweepOptions so = o;
    so.output_dir = (fs::path(a.baseline) / "statistics-runs").string();
    if (!a.resume) fs::remove_all(fs::path(so.output_dir) / "runs");
    nlohmann::json runs = run_sweep(many, so);
    nlohmann::json statistics_json = make_distribution_baseline(runs, so.output_dir, a.baseline, a.distribution);
    add_same_seed_records(statistics_json, fresh, o.output_dir, a.baseline);
    write_json_atomic(statistics_path.string(), statistics_json);
    fs::remove_all(so.output_dir);
    std::printf("baseline updated: %s (%zu runs; statistics of %zu runs in %s); review with git diff %s\n",
                a.baseline.c_str(), fresh["runs"].size(), runs["runs"].size(), statistics_path.string().c_str(),
                a.baseline.c_str());
    return 0;
  }
  CheckOutcome medians = check_against_baseline(fresh, baseline, {a.sigmas, a.min_relative});
  std::printf("## Medians over seeds against the baseline's\n\n");
  std::fputs(medians.table.c_str(), stdout);
  bool passed = medians.passed;
  int failures = medians.failures;
  nlohmann::json record = {{"medians", {{"passed", medians.passed}, {"failures", medians.failures}, {"flip", medians.flip}}}};
  if (statistics.is_null()) {
    std::printf("\nNo %s: the distribution tests need a baseline made with --update.\n", statistics_path.string().c_str());
  } else {
    DistributionOutcome tests = check_distribution(fresh, o.output_dir, statistics, a.baseline, a.distribution);
    std::printf("\n## Seeds as samples: t-tests against the baseline's distribution\n\n");
    std::fputs(tests.table.c_str(), stdout);
    passed = passed && tests.passed;
    failures += tests.failures;
    record["distribution"] = {{"passed", tests.passed},
                              {"failures", tests.failures},
                              {"alpha", a.distribution.alpha},
                              {"whole_image_threshold", tests.whole_image_threshold},
                              {"block_threshold", tests.block_threshold},
                              {"inject_bias", a.distribution.inject_bias},
                              {"inject_variance", a.distribution.inject_variance},
                              {"inject_method", a.distribution.inject_method},
                              {"same_seed_margin", a.distribution.same_seed_margin},
                              {"groups", tests.groups}};
    // The fresh runs as a baseline's same-seed records (scripts/check_power.py pairs with them).
    write_json_atomic((fs::path(o.output_dir) / "same_seeds.json").string(), tests.same_seeds);
  }
  record["passed"] = passed;
  write_json_atomic((fs::path(o.output_dir) / "check.json").string(), record);
  std::printf("metrics check %s: %d failure(s); fresh results in %s\n", passed ? "passed" : "FAILED", failures,
              o.output_dir.c_str());
  return passed ? 0 : 1;
}

}  // namespace sst::app
