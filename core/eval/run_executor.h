// Renders one run of a sweep and measures it: equal-time calibration when the run has a time
// budget, `repeat` timed renders, metrics against the reference, and the run's files, written
// so that run.json appears last (its presence means the run is complete).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "core/eval/experiment_config.h"
#include "core/image/image.h"
#include "core/pipeline/renderer.h"
#include "core/scene/scene.h"

namespace sst {

// spp that makes the frame time meet `budget_ms`, from a linear model t = fixed + per_spp * spp
// fitted to two probe renders. `probes` receives what was measured.
int calibrate_spp(const Scene& scene, const RunSpec& run, double budget_ms, nlohmann::json* probes);

struct RunReference {
  std::string id;
  nlohmann::json description;  // kind and parameters, for results.json
  const Image* image = nullptr;
};

// Renders `run` and writes <run_dir>/image.exr, image.png, error.png, then run.json. Returns the
// run's record (the schema of core/eval/README.md, without the cross-run fields).
nlohmann::json execute_run(const Scene& scene, const RunSpec& run, const RunReference& reference,
                           const std::string& run_dir);

}  // namespace sst
