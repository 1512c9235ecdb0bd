// `sst-eval compare A B`: the metrics of a test image A against a reference B.
#pragma once
#include <string>

namespace CLI {
class App;
}

namespace sst::app {

struct CompareArgs {
  std::string test;          // A
  std::string reference;     // B
  bool json = false;         // one JSON object on stdout instead of the table
  std::string heatmap;       // where to write the relative-error heat map (empty: none)
  float heatmap_max = 1.0f;  // relative error shown as the brightest colour
  std::string layer;         // compare this EXR layer of both files instead of their RGB
  std::string mask;          // also report the errors where this image is 0 (empty: none)
  std::string flip_map;      // where to write the LDR-FLIP error map (empty: none)
  std::string flip_hdr_map;  // where to write the HDR-FLIP error map (empty: none)
};

// Registers the subcommand on app, filling args when it is parsed.
CLI::App* add_compare_command(CLI::App& app, CompareArgs& args);
// Throws sst::Error for bad input (missing file, mismatched sizes, absent layer).
int run_compare(const CompareArgs& args);

}  // namespace sst::app
