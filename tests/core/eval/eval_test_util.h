// What the eval tests share: a results.json without the fields that depend on timing, for
// comparing two sweeps that must agree in everything else.
#pragma once
#include <nlohmann/json.hpp>

namespace sst::test {

inline nlohmann::json without_timings(nlohmann::json r) {
  r.erase("machine");
  for (nlohmann::json& run : r["runs"]) {
    for (const char* k : {"time_ms", "stages", "counters", "efficiency", "ssim_gain_pct_per_ms", "gain_base"}) run.erase(k);
    run["reference_description"].erase("render_ms");
  }
  for (nlohmann::json& g : r["groups"]) g.erase("time_ms_median"), g.erase("pareto");
  for (auto& [id, ref] : r["references"].items()) ref.erase("render_ms");
  return r;
}

}  // namespace sst::test
