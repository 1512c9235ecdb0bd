#include "core/eval/report.h"
#include "core/eval/json_fields.h"

#include <filesystem>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/eval/svg_plot.h"
#include "core/util/json_io.h"

namespace sst {
namespace {

using nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const char* const kDash = "\u2014";

// ---- tolerant JSON access: a missing or null field is a dash in the page, not an exception

// Strings as they are, other values as JSON text (numbers, booleans), null as "".
std::string text_of(const json& j) {
  if (j.is_string()) return j.get<std::string>();
  return j.is_null() ? "" : j.dump();
}
std::string text_of(const json& j, const char* key) { return text_of(member(j, key)); }

// ---- formatting

std::string esc(std::string_view s) { return xml_escape(s); }

// Paths from results.json as URLs relative to the page: percent-encoding everything but
// unreserved characters and '/' keeps '#', '?', spaces and any "scheme:" from changing what the
// browser loads.
std::string url(std::string_view path) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : path) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (alnum || c == '-' || c == '_' || c == '.' || c == '~' || c == '/') {
      out += char(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return esc(out);
}

// 4 significant digits; scientific outside [1e-3, 1e5) where fixed notation gets too wide.
std::string fmt(double v, int significant = 4) {
  if (!std::isfinite(v)) return kDash;
  if (v == 0.0) return "0";
  char buf[64];
  const double a = std::abs(v);
  if (a >= 1e5 || a < 1e-3) {
    std::snprintf(buf, sizeof(buf), "%.*e", significant - 1, v);
    std::string s = buf;
    const size_t e = s.find('e');
    return s.substr(0, e + 1) + std::to_string(std::atoi(s.c_str() + e + 1));
  }
  const int decimals = std::max(0, significant - 1 - int(std::floor(std::log10(a))));
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

// Counts (spp) in full, without a decimal point.
std::string fmt_count(double v) {
  if (!std::isfinite(v)) return kDash;
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.0f", v);
  return buf;
}

std::string td(const std::string& html, const char* cls = "num") {
  return std::string("<td class=\"") + cls + "\">" + html + "</td>";
}

double mean_finite(const std::vector<double>& values) {
  double sum = 0.0;
  int n = 0;
  for (double v : values)
    if (std::isfinite(v)) sum += v, ++n;
  return n ? sum / n : kNaN;
}

// ---- the results, indexed by scene

struct Scene {
  std::string name;
  std::vector<const json*> groups;
  std::vector<const json*> runs;
  std::vector<std::string> references;  // ids, in order of first use
};

struct Index {
  const json* results = nullptr;
  std::map<std::string, const json*> runs_by_id;
  std::vector<Scene> scenes;
  // Plot series name -> colour/marker index: each label keeps its colour in every plot.
  mutable std::map<std::string, int> styles;

  int style(const std::string& series_name) const {
    return styles.try_emplace(series_name, int(styles.size())).first->second;
  }

  Scene& scene(const std::string& name) {
    for (Scene& s : scenes)
      if (s.name == name) return s;
    scenes.push_back({name, {}, {}, {}});
    return scenes.back();
  }
  const json& reference(const std::string& id) const { return member(member(*results, "references"), id.c_str()); }
  std::vector<const json*> runs_of(const json& group) const {
    std::vector<const json*> out;
    for (const json& id : member(group, "runs")) {
      auto it = runs_by_id.find(text_of(id));
      if (it != runs_by_id.end()) out.push_back(it->second);
    }
    return out;
  }
};

Index build_index(const json& results) {
  Index index;
  index.results = &results;
  for (const json& g : member(results, "groups")) {
    index.scene(text_of(g, "scene")).groups.push_back(&g);
    index.style(text_of(g, "label"));
  }
  for (const json& r : member(results, "runs")) {
    index.runs_by_id[text_of(r, "id")] = &r;
    Scene& s = index.scene(text_of(r, "scene"));
    s.runs.push_back(&r);
    const std::string ref = text_of(r, "reference");
    if (!ref.empty() && std::find(s.references.begin(), s.references.end(), ref) == s.references.end())
      s.references.push_back(ref);
  }
  return index;
}

// "vpls=10000, block_size=8" (keys in JSON order, which nlohmann sorts).
// A config names the built-in scene "" (no file).
std::string scene_title(const std::string& name) { return name.empty() ? "built-in Cornell box" : name; }

std::string axes_text(const json& axes, const std::string& skip = "") {
  std::string s;
  if (!axes.is_object()) return s;
  for (auto it = axes.begin(); it != axes.end(); ++it) {
    if (it.key() == skip) continue;
    s += (s.empty() ? "" : ", ") + it.key() + "=" + text_of(it.value());
  }
  return s;
}

// The run whose image stands for its group: seed 0, else the lowest seed.
const json* representative_run(const Index& index, const json& group) {
  const json* best = nullptr;
  for (const json* r : index.runs_of(group))
    if (!best || number(*r, "seed") < number(*best, "seed")) best = r;
  return best;
}

// ---- header

// "path tracer, 1024 spp, 8 bounces, 640×480": what a reader needs to judge the reference.
std::string reference_summary(const json& ref) {
  const json& p = member(ref, "params");
  const std::string kind = text_of(ref, "kind");
  std::string s = kind == "path" ? "path tracer" : kind == "vpl" ? "VPL ground truth" : kind;
  if (kind == "vpl" && member(p, "method").is_string()) s += " (" + text_of(p, "method") + ")";
  const std::vector<std::pair<const char*, const char*>> parts{
      {"spp", " spp"}, {"max_bounces", " bounces"}, {"vpls", " VPLs"}, {"vpl_max_bounces", " VPL bounces"}};
  for (const auto& [key, unit] : parts)
    if (member(p, key).is_number()) s += ", " + text_of(p, key) + unit;
  if (member(p, "width").is_number() && member(p, "height").is_number())
    s += ", " + text_of(p, "width") + "\u00d7" + text_of(p, "height");
  if (member(p, "diffuse_only") == true) s += ", diffuse only";
  return s;
}

std::string machine_summary(const json& m) {
  if (!m.is_object()) return text_of(m);
  std::string s;
  auto add = [&](const std::string& part) { s += (s.empty() ? "" : "; ") + part; };
  if (m.contains("cpu")) add(text_of(m, "cpu"));
  for (const char* key : {"hardware_threads", "threads"})
    if (m.contains(key)) add(text_of(m, key) + " threads");
  for (auto it = m.begin(); it != m.end(); ++it)
    if (it.key() != "cpu" && it.key() != "hardware_threads" && it.key() != "threads")
      add(it.key() + ": " + text_of(it.value()));
  return s;
}

std::string fact(const std::string& name, const std::string& html) {
  return "<tr><th>" + name + "</th><td>" + html + "</td></tr>\n";
}

std::string references_table(const Index& index) {
  std::string s = "<table class=\"refs\"><tr><th>scene</th><th>reference</th><th>what</th><th>render time</th></tr>\n";
  for (const Scene& scene : index.scenes) {
    for (const std::string& id : scene.references) {
      const json& ref = index.reference(id);
      s += "<tr><td>" + esc(scene_title(scene.name)) + "</td><td><code>" + esc(id) + "</code></td><td>" +
           esc(reference_summary(ref)) + "</td>" + td(fmt(number(ref, "render_ms") / 1000.0) + " s") + "</tr>\n";
    }
  }
  return s + "</table>\n";
}

std::string header_html(const Index& index) {
  const json& r = *index.results;
  const size_t runs = member(r, "runs").size(), groups = member(r, "groups").size();
  std::string s = "<h1>sst-eval report: " + esc(text_of(r, "name")) + "</h1>\n<table class=\"facts\">\n";
  s += fact("tool revision", "<code>" + esc(text_of(r, "tool_revision")) + "</code>");
  s += fact("machine", esc(machine_summary(member(r, "machine"))));
  s += fact("device", esc(text_of(r, "device")));
  s += fact("runs", std::to_string(runs) + " runs in " + std::to_string(groups) + " groups over " +
                        std::to_string(index.scenes.size()) + " scene(s)");
  s += "</table>\n<h3>Metrics are against</h3>\n" + references_table(index);
  return s;
}

// ---- group table

// The sweep axes of a scene's groups, one column each; spp has its own column (the spp rendered).
std::vector<std::string> axis_names(const Scene& scene) {
  std::set<std::string> names;
  for (const json* g : scene.groups)
    if (member(*g, "axes").is_object())
      for (auto it = member(*g, "axes").begin(); it != member(*g, "axes").end(); ++it) names.insert(it.key());
  names.erase("spp");
  return {names.begin(), names.end()};
}

std::vector<double> run_values(const std::vector<const json*>& runs, const char* object, const char* key) {
  std::vector<double> out;
  for (const json* r : runs) out.push_back(object ? number(member(*r, object), key) : number(*r, key));
  return out;
}

// "12.3 [12.0..13.1]": the group's median of run medians, and the extremes over all repeats.
std::string time_cell(const json& group, const std::vector<const json*>& runs) {
  double lo = kNaN, hi = kNaN;
  for (const json* r : runs) {
    const double mn = number(member(*r, "time_ms"), "min"), mx = number(member(*r, "time_ms"), "max");
    if (std::isfinite(mn)) lo = std::isfinite(lo) ? std::min(lo, mn) : mn;
    if (std::isfinite(mx)) hi = std::isfinite(hi) ? std::max(hi, mx) : mx;
  }
  double median = number(group, "time_ms_median");
  if (!std::isfinite(median)) median = mean_finite(run_values(runs, "time_ms", "median"));
  std::string s = fmt(median);
  if (std::isfinite(lo) && std::isfinite(hi)) s += " <span class=\"range\">[" + fmt(lo) + ".." + fmt(hi) + "]</span>";
  return s;
}

// The spp rendered; a range when equal-time calibration gave the seeds different counts.
std::string spp_cell(const std::vector<const json*>& runs) {
  std::vector<double> spp = run_values(runs, nullptr, "spp");
  std::erase_if(spp, [](double v) { return !std::isfinite(v); });
  if (spp.empty()) return kDash;
  const auto [lo, hi] = std::minmax_element(spp.begin(), spp.end());
  std::string s = fmt_count(*lo) + (*lo == *hi ? "" : "\u2013" + fmt_count(*hi));
  if (!runs.empty() && member(*runs.front(), "time_budget_ms").is_number())
    s += " <span class=\"range\">(budget " + fmt(number(*runs.front(), "time_budget_ms")) + " ms)</span>";
  return s;
}

std::string rmse_cell(const json& group) {
  const double std_dev = number(group, "rmse_std");
  return fmt(number(group, "rmse_mean")) + (std::isfinite(std_dev) ? " \u00b1 " + fmt(std_dev, 2) : "");
}

std::string group_row(const Index& index, const json& g, const std::vector<std::string>& axes) {
  const std::vector<const json*> runs = index.runs_of(g);
  const bool pareto = member(g, "pareto") == true;
  double ssim = number(g, "ssim_mean");
  if (!std::isfinite(ssim)) ssim = mean_finite(run_values(runs, "metrics", "ssim"));
  std::string s = pareto
                      ? "<tr class=\"pareto\"><td class=\"mark\" title=\"on the RMSE-vs-time Pareto front\">\u2605</td>"
                      : "<tr><td class=\"mark\"></td>";
  s += td(esc(text_of(g, "label")), "label");
  for (const std::string& a : axes) {
    const json& v = member(member(g, "axes"), a.c_str());
    s += td(v.is_null() ? kDash : esc(text_of(v)));
  }
  s += td(spp_cell(runs)) + td(time_cell(g, runs)) + td(rmse_cell(g));
  s += td(fmt(mean_finite(run_values(runs, "metrics", "rel_mse"))));
  s += td(fmt(mean_finite(run_values(runs, "metrics", "psnr"))));
  s += td(fmt(ssim)) + td(fmt(mean_finite(run_values(runs, nullptr, "efficiency"))));
  s += td(fmt(mean_finite(run_values(runs, nullptr, "ssim_gain_pct_per_ms"))));
  s += td(fmt(number(g, "bias2"))) + td(fmt(number(g, "variance"))) + td(std::to_string(runs.size()));
  return s + "</tr>\n";
}

std::string group_table(const Index& index, const Scene& scene) {
  const std::vector<std::string> axes = axis_names(scene);
  std::string s = "<table class=\"groups\"><thead><tr><th title=\"Pareto front\">\u2605</th><th>label</th>";
  for (const std::string& a : axes) s += "<th>" + esc(a) + "</th>";
  s += "<th>spp</th><th>time ms<br><span class=\"range\">median [min..max]</span></th>"
       "<th>RMSE<br><span class=\"range\">mean \u00b1 std</span></th><th>rel MSE</th><th>PSNR dB</th><th>SSIM</th>"
       "<th>efficiency 1/s</th><th>SSIM gain %/ms</th><th>bias\u00b2</th><th>variance</th><th>seeds</th>"
       "</tr></thead>\n<tbody>\n";
  for (const json* g : scene.groups) s += group_row(index, *g, axes);
  return s +
         "</tbody></table>\n<p class=\"note\">\u2605 on the RMSE-vs-time Pareto front of this scene. Time, "
         "RMSE, SSIM, bias\u00b2 and variance are over the group's seeds; rel MSE, PSNR, efficiency and SSIM "
         "gain are means over its runs.</p>\n";
}

// ---- plots

std::string figure(const Plot& plot) {
  if (drawable_point_count(plot) < 2) return "";
  return "<figure class=\"plot\">" + render_svg(plot) + "</figure>\n";
}

void sort_by_x(std::vector<PlotPoint>& points) {
  std::stable_sort(points.begin(), points.end(), [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
}

// Appends a point to the series named `name`, creating it in order of first appearance.
void add_point(const Index& index, Plot& plot, const std::string& name, PlotPoint p) {
  for (PlotSeries& s : plot.series)
    if (s.name == name) return s.points.push_back(p);
  plot.series.push_back({name, {p}, true, index.style(name)});
}

Plot rmse_time_plot(const Index& index, const Scene& scene) {
  Plot plot;
  plot.title = "RMSE vs time: " + scene_title(scene.name);
  plot.x = {"render time, ms (median)", AxisScale::log10};
  plot.y = {"RMSE (mean over seeds)", AxisScale::log10};
  plot.highlight.name = "Pareto front";
  for (const json* g : scene.groups) {
    const PlotPoint p{number(*g, "time_ms_median"), number(*g, "rmse_mean")};
    add_point(index, plot, text_of(*g, "label"), p);
    if (member(*g, "pareto") == true) plot.highlight.points.push_back(p);
  }
  for (PlotSeries& s : plot.series) sort_by_x(s.points);
  sort_by_x(plot.highlight.points);
  return plot;
}

double vpl_count(const Index& index, const json& group) {
  const std::vector<const json*> runs = index.runs_of(group);
  const double v = runs.empty() ? kNaN : number(member(*runs.front(), "params"), "vpls");
  return std::isfinite(v) ? v : number(member(group, "axes"), "vpls");
}

bool vpls_vary(const Scene& scene) {
  std::set<double> values;
  for (const json* g : scene.groups) {
    const double v = number(member(*g, "axes"), "vpls");
    if (std::isfinite(v)) values.insert(v);
  }
  return values.size() >= 2;
}

// One series per label and setting of the other axes, so each line varies the VPL count alone.
Plot vpl_plot(const Index& index, const Scene& scene, bool rmse) {
  Plot plot;
  plot.title = (rmse ? "RMSE vs VPL count: " : "Time vs VPL count: ") + scene_title(scene.name);
  plot.x = {"VPLs", AxisScale::log10};
  plot.y = rmse ? PlotAxis{"RMSE (mean over seeds)", AxisScale::log10}
                : PlotAxis{"render time, ms (median)", AxisScale::linear};
  for (const json* g : scene.groups) {
    const std::string others = axes_text(member(*g, "axes"), "vpls");
    const std::string name = text_of(*g, "label") + (others.empty() ? "" : " " + others);
    const double vpls = vpl_count(index, *g);  // methods without VPLs (pt) have no place here
    if (std::isfinite(vpls)) add_point(index, plot, name, {vpls, number(*g, rmse ? "rmse_mean" : "time_ms_median")});
  }
  for (PlotSeries& s : plot.series) sort_by_x(s.points);
  return plot;
}

std::string plots_html(const Index& index, const Scene& scene) {
  std::string s = figure(rmse_time_plot(index, scene));
  if (vpls_vary(scene)) s += figure(vpl_plot(index, scene, true)) + figure(vpl_plot(index, scene, false));
  return s.empty() ? "" : "<div class=\"plots\">\n" + s + "</div>\n";
}

// ---- image comparison

// The pane keeps the image's aspect ratio so that zooming scrolls inside it instead of growing it.
std::string pane_style(const json& run) {
  const double w = number(member(run, "params"), "width"), h = number(member(run, "params"), "height");
  if (!(w > 0 && h > 0)) return "";
  return " style=\"aspect-ratio: " + fmt_count(w) + " / " + fmt_count(h) + "\"";
}

std::string reference_card(const Index& index, const std::string& id, const std::string& style) {
  const json& ref = index.reference(id);
  return "<div class=\"card ref\"><h4>reference <code>" + esc(id) + "</code></h4><p class=\"sub\">" +
         esc(reference_summary(ref)) + "</p><figure><div class=\"pane\"" + style + "><img src=\"" +
         url(text_of(ref, "image_png")) +
         "\" alt=\"reference\"></div><figcaption>reference</figcaption>"
         "</figure></div>\n";
}

std::string run_card(const Index& index, const json& group, const json& run) {
  const json& images = member(run, "images");
  const std::string id = text_of(run, "id"), style = pane_style(run);
  const std::string ref_png = text_of(index.reference(text_of(run, "reference")), "image_png");
  const std::string axes = axes_text(member(group, "axes"));
  std::string s = "<div class=\"card\"><h4>" + esc(text_of(group, "label")) +
                  (axes.empty() ? "" : " <span class=\"axes\">" + esc(axes) + "</span>") + "</h4>";
  s += "<p class=\"sub\">run <code>" + esc(id) + "</code> (seed " + esc(text_of(run, "seed")) + "), RMSE " +
       fmt(number(member(run, "metrics"), "rmse")) + ", SSIM " + fmt(number(member(run, "metrics"), "ssim")) + ", " +
       fmt(number(member(run, "time_ms"), "median")) + " ms</p><div class=\"pair\">";
  s += "<figure><div class=\"pane\"" + style + "><img class=\"flip\" src=\"" + url(text_of(images, "png")) +
       "\" data-run=\"" + url(text_of(images, "png")) + "\" data-ref=\"" + url(ref_png) + "\" data-id=\"" + esc(id) +
       "\" alt=\"run " + esc(id) +
       "\" title=\"click: flip between this run and the reference\"></div>"
       "<figcaption>showing <b class=\"which\">run " +
       esc(id) + "</b> (click to flip)</figcaption></figure>";
  // A pruned results folder keeps no heat maps (sst-eval sweep writes them; prune_results.sh drops them).
  if (!text_of(images, "error_png").empty())
    s += "<figure><div class=\"pane\"" + style + "><img src=\"" + url(text_of(images, "error_png")) +
         "\" alt=\"error of " + esc(id) +
         "\"></div><figcaption>relative error, 0 (black) .. \u22651 (yellow) "
         "<span class=\"ramp\"></span></figcaption></figure>";
  return s + "</div></div>\n";
}

std::string comparison_html(const Index& index, const Scene& scene) {
  std::string cards;
  const std::string style = scene.runs.empty() ? "" : pane_style(*scene.runs.front());
  for (const std::string& id : scene.references) cards += reference_card(index, id, style);
  for (const json* g : scene.groups)
    if (const json* run = representative_run(index, *g)) cards += run_card(index, *g, *run);
  if (cards.empty()) return "";
  return "<div class=\"compare\"><div class=\"controls\">zoom <select class=\"zoom\"><option value=\"fit\">fit"
         "</option><option value=\"1\">1\u00d7</option><option value=\"2\">2\u00d7</option><option value=\"4\">"
         "4\u00d7</option><option value=\"8\">8\u00d7</option></select> <button class=\"flip-all\">show all "
         "references</button> <span class=\"note\">one run per group (seed 0); click an image to flip it "
         "with its reference; the panes scroll together</span></div>\n<div class=\"cards\">\n" +
         cards + "</div></div>\n";
}

// ---- scene section, runs table, page

std::string scene_html(const Index& index, const Scene& scene) {
  std::string s = "<section class=\"scene\"><h2>" + esc(scene_title(scene.name)) + "</h2>\n";
  for (const std::string& id : scene.references)
    s += "<p class=\"sub\">metrics against reference <code>" + esc(id) +
         "</code>: " + esc(reference_summary(index.reference(id))) + "</p>\n";
  if (!scene.groups.empty()) s += group_table(index, scene);
  s += plots_html(index, scene);
  s += "<h3>Images</h3>\n" + comparison_html(index, scene);
  return s + "</section>\n";
}

std::string runs_table(const Index& index) {
  const json& runs = member(*index.results, "runs");
  std::string s = "<details class=\"runs\"><summary>All " + std::to_string(runs.size()) +
                  " runs</summary>\n<table><thead><tr><th>id</th><th>label</th><th>scene</th><th>seed</th><th>spp"
                  "</th><th>time ms</th><th>RMSE</th><th>SSIM</th></tr></thead><tbody>\n";
  for (const json& r : runs) {
    s += "<tr>" + td("<code>" + esc(text_of(r, "id")) + "</code>", "id") + td(esc(text_of(r, "label")), "label") +
         td(esc(scene_title(text_of(r, "scene"))), "label") + td(esc(text_of(r, "seed"))) + td(esc(text_of(r, "spp"))) +
         td(fmt(number(member(r, "time_ms"), "median"))) + td(fmt(number(member(r, "metrics"), "rmse"))) +
         td(fmt(number(member(r, "metrics"), "ssim"))) + "</tr>\n";
  }
  return s + "</tbody></table></details>\n";
}

const char* const kStyle = R"(<style>
body { font: 14px/1.45 system-ui, sans-serif; margin: 24px; color: #222; background: #fafafa; }
h1 { font-size: 22px; margin: 0 0 12px; } h2 { font-size: 19px; margin: 0 0 6px; }
h3 { font-size: 15px; margin: 18px 0 6px; } h4 { font-size: 14px; margin: 0; }
code { font: 12px ui-monospace, monospace; }
table { border-collapse: collapse; background: #fff; }
th, td { border: 1px solid #ddd; padding: 3px 7px; vertical-align: top; }
th { background: #f0f0f0; font-weight: 600; text-align: left; }
table.facts th { width: 9em; }
table.groups th { text-align: center; font-size: 13px; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.mark { text-align: center; color: #c58b00; }
tr.pareto td { background: #fff8e1; } tr.pareto td.label { font-weight: 600; }
.range, .sub, .note, .axes { color: #666; font-size: 12px; font-weight: normal; }
section.scene { background: #fff; border: 1px solid #ddd; border-radius: 6px; padding: 14px 18px; margin: 20px 0; }
.plots { display: flex; flex-wrap: wrap; gap: 12px; margin-top: 12px; }
figure { margin: 0; } figcaption { font-size: 12px; color: #444; margin-top: 3px; }
.controls { margin: 6px 0 10px; } .cards { display: flex; flex-wrap: wrap; gap: 14px; }
.card { border: 1px solid #ddd; border-radius: 4px; padding: 8px; background: #fcfcfc; }
.card .sub { margin: 2px 0 6px; } .pair { display: flex; gap: 8px; }
.pane { width: 300px; max-height: 70vh; overflow: auto; background: #000; }
.pane img { display: block; width: 100%; image-rendering: pixelated; }
img.flip { cursor: pointer; }
.ramp { display: inline-block; width: 80px; height: 9px; vertical-align: middle; border: 1px solid #999;
  background: linear-gradient(90deg, #000004, #420a68, #932667, #dd513a, #fca50a, #fcffa4); }
details.runs { margin-top: 20px; } details.runs summary { cursor: pointer; font-weight: 600; }
</style>
)";

// Flip, zoom and synchronised scrolling, per .compare block.
const char* const kScript = R"(<script>
function show(img, ref) {
  img.src = ref ? img.dataset.ref : img.dataset.run;
  img.dataset.showing = ref ? 'ref' : 'run';
  img.closest('figure').querySelector('.which').textContent = ref ? 'reference' : 'run ' + img.dataset.id;
}
document.querySelectorAll('.compare').forEach(function (box) {
  var imgs = box.querySelectorAll('img.flip'), panes = box.querySelectorAll('.pane'), all = false, busy = false;
  imgs.forEach(function (img) {
    img.addEventListener('click', function () { show(img, img.dataset.showing !== 'ref'); });
  });
  box.querySelector('.flip-all').addEventListener('click', function (e) {
    all = !all;
    imgs.forEach(function (img) { show(img, all); });
    e.target.textContent = all ? 'show all runs' : 'show all references';
  });
  box.querySelector('.zoom').addEventListener('change', function (e) {
    var z = e.target.value;
    box.querySelectorAll('.pane img').forEach(function (img) {
      img.style.width = z === 'fit' ? '100%' : (img.naturalWidth * z) + 'px';
    });
  });
  panes.forEach(function (p) {
    p.addEventListener('scroll', function () {
      if (busy) return;
      busy = true;
      panes.forEach(function (q) { if (q !== p) { q.scrollLeft = p.scrollLeft; q.scrollTop = p.scrollTop; } });
      requestAnimationFrame(function () { busy = false; });
    });
  });
});
</script>
)";

}  // namespace

std::string make_report_html(const nlohmann::json& results) {
  const Index index = build_index(results);
  std::string s = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>sst-eval report: " +
                  esc(text_of(results, "name")) + "</title>\n" + kStyle + "</head><body>\n";
  s += header_html(index);
  for (const Scene& scene : index.scenes) s += scene_html(index, scene);
  s += runs_table(index);
  return s + kScript + "</body></html>\n";
}

// Image paths whose files are gone (a results folder pruned for committing) become null, so the
// page shows a dash instead of a broken image.
nlohmann::json without_missing_images(nlohmann::json results, const std::string& dir) {
  auto present = [&](const nlohmann::json& path) {
    return path.is_string() && std::filesystem::exists(std::filesystem::path(dir) / path.get<std::string>());
  };
  for (nlohmann::json& run : results["runs"])
    if (run.contains("images"))
      for (auto& [kind, path] : run["images"].items())
        if (!present(path)) path = nullptr;
  for (auto& [id, ref] : results["references"].items())
    if (ref.contains("image_png") && !present(ref["image_png"])) ref["image_png"] = nullptr;
  return results;
}

void write_report(const nlohmann::json& results, const std::string& results_dir) {
  write_text_atomic(results_dir + "/report.html", make_report_html(without_missing_images(results, results_dir)));
}

}  // namespace sst
