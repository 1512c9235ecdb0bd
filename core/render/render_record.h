// The JSON record of a render: what ran, where, with which parameters, on which scene (and what
// that scene requires), how long each stage took and what work it did.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/render/renderer.h"
#include "core/scene/scene.h"
#include "core/util/json_io.h"

namespace sst {

inline constexpr int kRecordSchemaVersion = 1;

// Medians with min and max over the runs, per stage: {"render": {"median":..,"min":..,"max":..}}.
nlohmann::json stage_statistics(const std::vector<StageTimer>& timers);

// The device a render ran on: {"backend", "name"}.
nlohmann::json device_record(const RenderOptions& options);

// `runs` are repeats of the same render (their images are identical; timings differ).
nlohmann::json make_render_record(const std::string& tool, const Scene& scene, const std::vector<RenderResult>& runs,
                                  const StageTimer& load, const StageTimer& write);

}  // namespace sst
