#include "core/pipeline/render_record.h"

#include <algorithm>
#include <thread>

#include <embree3/rtcore_config.h>
#include <tbb/info.h>

#include "core/scene/scene_summary.h"
#include "core/util/machine_info.h"
#include "core/util/params.h"
#include "core/util/statistics.h"

namespace sst {

nlohmann::json stage_statistics(const std::vector<StageTimer>& timers) {
  nlohmann::json j = nlohmann::json::object();
  if (timers.empty()) return j;
  for (const auto& [stage, ms0] : timers.front().stages()) {
    std::vector<double> v;
    for (const StageTimer& t : timers) v.push_back(t.ms(stage));
    j[stage] = median_min_max(v);
  }
  return j;
}

nlohmann::json cpu_device_record(const RenderOptions& options) {
  int threads = options.threads > 0 ? options.threads : tbb::info::default_concurrency();
  return {{"backend", "cpu"},
          {"name", "CPU: Embree " RTC_VERSION_STRING ", oneTBB, " + std::to_string(threads) + " threads"}};
}

nlohmann::json vulkan_device_record(const DeviceInfo& d, const nlohmann::json& setup) {
  return {{"backend", "vulkan"},
          {"index", d.index},
          {"name", d.name},
          {"type", d.type},
          {"driver", d.driver},
          {"api_version", api_version_string(d.api_version)},
          {"ray_query", d.ray_query},
          {"setup", setup}};
}

nlohmann::json make_render_record(const std::string& tool, const Scene& scene, const std::vector<RenderResult>& runs,
                                  const StageTimer& load, const StageTimer& write) {
  const RenderResult& last = runs.back();
  nlohmann::json r;
  r["schema_version"] = kRecordSchemaVersion;
  r["tool"] = tool;
  r["revision"] = tool_revision();
  r["timestamp"] = utc_timestamp();
  r["machine"] = machine_info();
  r["device"] = last.device;
  r["scene"] = scene_summary(scene, last.options.diffuse_only);
  r["options"] = params_to_json(last.options);
  r["method_params"] = last.method_params;

  std::vector<StageTimer> timers;
  for (const RenderResult& run : runs) {
    StageTimer t = load;
    for (const auto& [stage, ms] : run.timer.stages()) t.add(stage, ms);
    for (const auto& [stage, ms] : write.stages()) t.add(stage, ms);
    timers.push_back(t);
  }
  r["repeat"] = runs.size();
  r["timings_ms"] = stage_statistics(timers);
  // Load and write happen once; their min = max = median.
  r["counters"] = last.frame.counters.to_json(frame_ms(last));
  r["method_counters"] = last.frame.method_counters;
  return r;
}

}  // namespace sst
