// What both front ends share: turning exceptions into one-line errors and exit codes.
#pragma once
#include <functional>

namespace sst::app {
// Runs body; an sst::Error or any std::exception becomes "error: <message>" on stderr and exit
// code 1 (2 for command-line usage errors, which CLI11 reports itself).
int run_guarded(const std::function<int()>& body);
}  // namespace sst::app
