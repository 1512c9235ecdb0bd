// report.html: what a person reads after a sweep. Built from results.json alone (docs/sst-eval.md
// describes it), so a report can be regenerated from any results folder without rendering.
// report_view() turns the results into a view model (JSON, keys in docs/sst-eval.md) and
// render_report() draws it with the templates of core/eval/report/, embedded in the binary.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace sst {

// The whole page as data: header, per-scene sections (group table, plots, image comparisons)
// and the table of all runs. Text is as shown (the template escapes it), image paths are URLs
// relative to the results folder. Missing or null fields show as a dash rather than failing, so a
// partial results.json still gives a page.
nlohmann::json report_view(const nlohmann::json& results);

// The page of a view model: one self-contained HTML file (inline CSS, SVG and script) except
// for the images it references. Deterministic (no date).
std::string render_report(const nlohmann::json& view);

// render_report(report_view(results)).
std::string make_report_html(const nlohmann::json& results);

// Writes results_dir/report.html atomically.
void write_report(const nlohmann::json& results, const std::string& results_dir);

// A figure of an image grid: a still image, or a video (an animated preview, shown looping and
// muted), by its path relative to the results folder; caption and aspect ("640 / 480") may be
// null. Image grids take these in their "figures" lists.
nlohmann::json image_figure(std::string_view path, std::string alt, nlohmann::json caption, nlohmann::json aspect);
nlohmann::json video_figure(std::string_view path, nlohmann::json caption, nlohmann::json aspect);

}  // namespace sst
