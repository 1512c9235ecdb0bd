// Renders one run of a sweep and measures it: equal-time calibration when the run has a time
// budget, `repeat` timed renders, metrics against the reference, and the run's files, written
// so that run.json appears last (its presence means the run is complete).
#pragma once
#include <functional>
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
  const Image* mask = nullptr;  // the emitter mask (reference "mask"); null: none
};

// The reference of a sequence's frame `index`, at `time`, rendered on the scene as posed then.
using FrameReference = std::function<RunReference(int index, double time, const Scene& posed)>;

// Renders `run` and writes <run_dir>/image.exr, image.png, error.png, then run.json. Returns the
// run's record (the schema of docs/sst-eval.md, without the cross-run fields). A sequence run
// (more than one frame, warm-up frames, temporal reuse, a denoiser or upsampling) is measured
// frame by frame against `frame_reference` instead of `reference`; `scene` is posed while it runs
// and restored after.
nlohmann::json execute_run(Scene& scene, const RunSpec& run, const RunReference& reference,
                           const FrameReference& frame_reference, const std::string& run_dir);

// Whether `run` renders a sequence (see execute_run).
bool is_sequence_run(const RunSpec& run);

}  // namespace sst
