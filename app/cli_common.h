// What both front ends share: parsing the command line and turning every error (CLI11's, JSON's,
// ours, the standard library's) into one line "error: ..." and an exit code.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace sst::app {
// Prints "error: <message>" on stderr as one line: line breaks become "; ", so that every error
// any part of the tool reports reads the same and a script can take the last line.
void print_error(const std::string& message);

// Parses the command line. Returns -1 when the program should go on, else its exit code: 0 after
// --help, 2 after a usage error (printed by print_error, not by CLI11's two-line formatter).
int parse_command_line(CLI::App& app, int argc, char** argv);

// Runs body; an sst::Error or any std::exception becomes print_error(<message>) and exit code 1.
int run_guarded(const std::function<int()>& body);
}  // namespace sst::app
