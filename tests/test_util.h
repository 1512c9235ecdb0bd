// Helpers shared by the tests: a fresh temporary folder, running a front end, finding scenes.
#pragma once
#include <filesystem>
#include <string>

namespace sst::test {
// A new empty folder under the system temp dir, named after the running test.
std::filesystem::path temp_dir();
struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};
// Runs a shell command line and captures its output.
CommandResult run_command(const std::string& command_line);
// ../shared/scenes/<relative>, or an empty path when the shared scenes are not beside the checkout.
std::filesystem::path shared_scene(const std::string& relative);
}  // namespace sst::test
