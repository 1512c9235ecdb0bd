// The experiment subcommands of sst-eval: sweep, merge, table and check. Each registers itself
// on the app and runs from its own args struct.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/eval/distribution_check.h"

namespace CLI {
class App;
}

namespace sst::app {

struct SweepArgs {
  std::string config;
  std::string output;  // default results/<name>
  bool resume = false;
  std::string shard;   // "i/n"; default from SLURM_ARRAY_TASK_ID/COUNT when present
  std::vector<std::string> scene_dirs;
  std::string cache_dir;
  bool quiet = false;
};
CLI::App* add_sweep_command(CLI::App& app, SweepArgs& args);
int run_sweep_command(const SweepArgs& args);

struct MergeArgs {
  std::vector<std::string> shard_dirs;
  std::string output;
};
CLI::App* add_merge_command(CLI::App& app, MergeArgs& args);
int run_merge_command(const MergeArgs& args);

struct TableArgs {
  std::string results;
  std::string format = "markdown";
  std::vector<std::string> stages;
};
CLI::App* add_table_command(CLI::App& app, TableArgs& args);
int run_table_command(const TableArgs& args);

struct ReportArgs {
  std::string results;  // results folder (or its results.json)
};
CLI::App* add_report_command(CLI::App& app, ReportArgs& args);
int run_report_command(const ReportArgs& args);

struct CheckArgs {
  std::string config;
  std::string baseline;
  std::string output;  // where the fresh results go (default: <tmp>/sst-check-<name>)
  bool update = false; // write the fresh results as the new baseline
  std::vector<std::string> scene_dirs;
  std::string cache_dir;
  double sigmas = 4.0;
  double min_relative = 0.05;
  int seeds = 0;          // > 0: overrides the config's seeds
  int64_t seed = -1;      // >= 0: overrides the config's first seed
  int statistics_seeds = 24;       // --update: seeds of the distribution statistics
  int64_t statistics_seed = 1000;  // --update: their first seed (disjoint from the check's)
  bool resume = false;    // keep finished runs in the output folder
  DistributionParams distribution;
  bool quiet = false;
};
CLI::App* add_check_command(CLI::App& app, CheckArgs& args);
int run_check_command(const CheckArgs& args);

}  // namespace sst::app
