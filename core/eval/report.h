// report.html: what a person reads after a sweep. Built from results.json alone (see README.md in
// this folder), so a report can be regenerated from any results folder without rendering.
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace sst {

// The whole page: header, per-scene group tables, plots (inline SVG), image comparisons and the
// table of all runs. Self-contained except for the images, referenced by their paths relative to
// the results folder. Deterministic (no date), every string from the JSON escaped; missing or
// null fields show as a dash rather than failing, so a partial results.json still gives a page.
std::string make_report_html(const nlohmann::json& results);

// Writes results_dir/report.html atomically.
void write_report(const nlohmann::json& results, const std::string& results_dir);

}  // namespace sst
