// results.json and results.csv of a sweep (schema: docs/sst-eval.md): the run records plus
// what needs all of them: per-group statistics over seeds (bias and variance), efficiency, the
// SST paper's SSIM gain per ms, and the error-vs-time Pareto front.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/eval/experiment_config.h"

namespace sst {

inline constexpr int kResultsSchemaVersion = 1;

// `runs`: the records execute_run wrote, any order. Images for bias/variance are read from
// `results_dir` (runs/<id>/image.exr, references/<ref>.exr).
nlohmann::json assemble_results(const ExperimentConfig& config, std::vector<nlohmann::json> runs,
                                const std::string& results_dir);

// One row per run; the axes of the config become columns.
std::string results_csv(const nlohmann::json& results);

// Writes results.json, results.csv and report.html into `dir`, each atomically.
void write_results(const nlohmann::json& results, const std::string& dir);

}  // namespace sst
