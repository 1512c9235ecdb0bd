// An experiment config (configs/*.json) and its expansion into runs. The parameter keys are the
// CLI's names (sst-render --list-methods); a key no render option and no method knows is an
// error naming the nearest valid key.
//
// | key            | meaning                                                                          |
// |----------------|----------------------------------------------------------------------------------|
// | name           | experiment name (default: the file's stem)                                       |
// | description    | free text, copied into the results                                               |
// | scenes / scene | scene names or paths (scene search path applies); "" = the built-in Cornell box  |
// | base           | parameters shared by every run (render options and method parameters)           |
// | <parameter>    | any parameter at the top level is shorthand for base.<parameter>                 |
// | axes           | {parameter: [values]}: their cartesian product is run, axes in name order, the last fastest |
// | variants       | [{name, params}]: named parameter sets, each run at every point of the axes     |
// | reference      | {kind: "path" or "vpl", <parameters of the reference render>} (reference.h)     |
// | seeds          | independent runs per point: seed, seed+1, ... (bias and variance when > 1)      |
// | repeat         | renders per run for timing (medians with min and max)                            |
// | time_budget_ms | equal-time mode: spp is calibrated per run so its frame time meets the budget    |
// | warmup_frames  | sequences: frames rendered before the measured ones (`frames`, a render option)  |
// | metrics_layer  | the run's layer compared with the reference: color (default), direct or indirect  |
// |                | (e.g. direct against a max_bounces 0 reference: the direct light alone)          |
// | paths          | sequences: key-frame paths moving cameras and lights (core/scene/key_frame_path.h) |
//
// A parameter that belongs only to other methods than a run's (e.g. vpls on a pt variant) does
// not apply to that run and is dropped from it; the run records what was in effect.
#pragma once
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace sst {

struct ExperimentVariant {
  std::string name;
  nlohmann::json params = nlohmann::json::object();
};

struct ExperimentConfig {
  std::string name;
  std::string description;
  std::vector<std::string> scenes;
  nlohmann::json base = nlohmann::json::object();
  std::vector<std::pair<std::string, std::vector<nlohmann::json>>> axes;  // by name (JSON objects are unordered)
  std::vector<ExperimentVariant> variants;  // empty: one unnamed variant
  nlohmann::json reference = nlohmann::json::object();
  int seeds = 1;
  int repeat = 1;
  int warmup_frames = 0;
  std::string metrics_layer = "color";
  nlohmann::json paths;   // null: none
  nlohmann::json source;  // the config as given
};

// One render of the sweep, fully specified.
struct RunSpec {
  int index = 0;
  std::string id;       // "0003-slc": unique and filesystem-safe
  std::string group;    // the run without its seed
  std::string label;    // variant name, else the method
  std::string scene;    // as named in the config
  std::string variant;  // "" when the config has no variants
  nlohmann::json axes = nlohmann::json::object();  // this run's values of the sweep axes
  uint32_t seed = 0;
  nlohmann::json options;        // RenderOptions keys in effect (method, spp, seed, width, ...)
  nlohmann::json method_params;  // the method's own parameters given (defaults not filled in)
  double time_budget_ms = 0.0;   // > 0: equal-time mode
  int repeat = 1;
  int warmup_frames = 0;         // a sequence's frames before those measured
  std::string metrics_layer = "color";  // FrameOutput layer compared with the reference
  nlohmann::json paths;          // the config's key-frame paths (null: none)
  std::string spec_hash;  // of everything above that determines the run's result
};

// `context` names the source (a file) in error messages.
ExperimentConfig parse_experiment_config(const nlohmann::json& j, const std::string& context);
ExperimentConfig load_experiment_config(const std::string& path);

// Every run, scene-major, then axes (by name, the last fastest), then variants, then seeds. Checks each
// run's parameters (unknown keys, impossible values) before anything is rendered.
// More runs than that (kMaxRuns) is an error naming the count, before any is expanded.
std::vector<RunSpec> expand_runs(const ExperimentConfig& config);
// The number of runs expand_runs would give (SIZE_MAX when it does not fit in size_t).
size_t count_runs(const ExperimentConfig& config);
// The most runs one config may have: far beyond any experiment (the largest in configs/ has a few
// hundred), far below what fills the memory when expanded (each run holds its JSON parameters).
constexpr size_t kMaxRuns = 100000;

// Every parameter name a config may use: render options, every method's parameters, and
// time_budget_ms.
std::vector<std::string> all_parameter_names();

}  // namespace sst
