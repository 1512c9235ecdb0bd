#include <CLI/CLI.hpp>

#include "app/cli_common.h"

int main(int argc, char** argv) {
  CLI::App app{"sst-render: render one image of a glTF scene"};
  CLI11_PARSE(app, argc, argv);
  return sst::app::run_guarded([] { return 0; });
}
