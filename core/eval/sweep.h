// `sst-eval sweep`: renders every run of an experiment (or one shard of them), each written
// atomically as it finishes, so that an interrupted sweep resumes where it stopped.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/eval/experiment_config.h"

namespace sst {

struct SweepOptions {
  std::string output_dir;               // results/<name> by default (set by the caller)
  bool resume = false;                  // keep finished runs found in output_dir
  int shard_index = 0;                  // this process renders runs with index % count == shard_index
  int shard_count = 1;
  std::vector<std::string> scene_dirs;  // --scene-dir
  std::string cache_dir;                // references ("" = default_reference_cache_dir())
  bool quiet = false;
};

// Parses "i/n" (0 <= i < n); sst::Error otherwise.
void parse_shard(const std::string& text, int& index, int& count);
// SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_COUNT, when set.
bool shard_from_slurm(int& index, int& count);

// Runs the sweep. Unsharded: writes results.json, results.csv and report.html and returns the
// results. Sharded: writes shards/shard-<i>-of-<n>.json (its runs) and returns that.
// An output folder that holds finished runs is an error unless `resume` (nothing is overwritten).
nlohmann::json run_sweep(const ExperimentConfig& config, const SweepOptions& options);

// Reads the finished run records under <dir>/runs; `runs` says which are expected (the ones
// whose spec_hash differs are stale and not returned).
std::vector<nlohmann::json> finished_runs(const std::string& dir, const std::vector<RunSpec>& runs);

}  // namespace sst
