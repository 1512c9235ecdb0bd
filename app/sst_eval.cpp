// sst-eval: one subcommand per task; each lives in its own app/eval_<name>.cpp, and this file
// only registers them and dispatches.
#include <CLI/CLI.hpp>

#include "app/cli_common.h"
#include "app/eval_compare.h"

int main(int argc, char** argv) {
  CLI::App app{"sst-eval: compare images and run experiments"};
  app.require_subcommand(1);
  sst::app::CompareArgs compare;
  CLI::App* compare_cmd = sst::app::add_compare_command(app, compare);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the message (and --help); its own codes are 100+, ours for usage errors is 2.
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (compare_cmd->parsed()) return sst::app::run_guarded([&] { return sst::app::run_compare(compare); });
  return 2;
}
