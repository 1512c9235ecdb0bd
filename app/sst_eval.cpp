// sst-eval: one subcommand per task (compare, sweep, merge, table, report, check); this file only
// registers them and dispatches.
#include <CLI/CLI.hpp>

#include "app/cli_common.h"
#include "app/eval_compare.h"
#include "app/eval_experiments.h"
#include "core/util/temp_files.h"

int main(int argc, char** argv) {
  CLI::App app{"sst-eval: compare images and run experiments"};
  app.require_subcommand(1);
  sst::app::CompareArgs compare;
  sst::app::SweepArgs sweep;
  sst::app::MergeArgs merge;
  sst::app::TableArgs table;
  sst::app::CheckArgs check;
  sst::app::ReportArgs report;
  CLI::App* compare_cmd = sst::app::add_compare_command(app, compare);
  CLI::App* sweep_cmd = sst::app::add_sweep_command(app, sweep);
  CLI::App* merge_cmd = sst::app::add_merge_command(app, merge);
  CLI::App* table_cmd = sst::app::add_table_command(app, table);
  CLI::App* check_cmd = sst::app::add_check_command(app, check);
  CLI::App* report_cmd = sst::app::add_report_command(app, report);
  if (int code = sst::app::parse_command_line(app, argc, argv); code >= 0) return code;
  sst::remove_temp_files_on_signals();
  using namespace sst::app;
  if (compare_cmd->parsed()) return run_guarded([&] { return run_compare(compare); });
  if (sweep_cmd->parsed()) return run_guarded([&] { return run_sweep_command(sweep); });
  if (merge_cmd->parsed()) return run_guarded([&] { return run_merge_command(merge); });
  if (table_cmd->parsed()) return run_guarded([&] { return run_table_command(table); });
  if (check_cmd->parsed()) return run_guarded([&] { return run_check_command(check); });
  if (report_cmd->parsed()) return run_guarded([&] { return run_report_command(report); });
  return 2;
}
