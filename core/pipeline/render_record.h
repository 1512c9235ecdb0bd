// The JSON record of a render: what ran, where, with which parameters, on which scene (and what
// that scene requires), how long each stage took and what work it did.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/pipeline/backend.h"
#include "core/pipeline/renderer.h"
#include "core/scene/scene.h"
#include "core/util/json_io.h"

namespace sst {

inline constexpr int kRecordSchemaVersion = 1;

// Medians with min and max over the runs, per stage: {"render": {"median":..,"min":..,"max":..}}.
nlohmann::json stage_statistics(const std::vector<StageTimer>& timers);

// The device a render ran on, as RenderResult::device holds it: {"backend", "name", ...}.
nlohmann::json cpu_device_record(const RenderOptions& options);
// Vulkan: the device's index, name, type, driver and API version, plus `setup` (what the backend
// uploaded, where the BVH was built).
nlohmann::json vulkan_device_record(const DeviceInfo& device, const nlohmann::json& setup);

// `runs` are repeats of the same render (their images are identical; timings differ).
nlohmann::json make_render_record(const std::string& tool, const Scene& scene, const std::vector<RenderResult>& runs,
                                  const StageTimer& load, const StageTimer& write);

}  // namespace sst
