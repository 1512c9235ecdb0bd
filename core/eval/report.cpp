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

#include "core/eval/page_template.h"
#include "core/eval/plot.h"
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

// ---- formatting (the view model holds text as shown; the template escapes it)

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
  return out;
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

// ---- the pieces of the view model (keys in docs/sst-eval.md). Every key a template reads is present,
// null when absent: Mustache looks a missing key up in the enclosing objects.

json span(std::string text, bool code = false) { return {{"text", std::move(text)}, {"code", code}}; }

json cell(std::string text, const char* cls = "num") {
  return {{"text", std::move(text)}, {"note", nullptr}, {"code", false},
          {"class", cls ? json(cls) : json(nullptr)}, {"title", nullptr}, {"header", false}};
}
json with(json cell, const char* key, json value) {
  cell[key] = std::move(value);
  return cell;
}
json code_cell(std::string text, const char* cls = nullptr) { return with(cell(std::move(text), cls), "code", true); }
json header_cell(std::string text) { return with(cell(std::move(text), nullptr), "header", true); }
json head_cell(std::string text, json note = nullptr) { return with(cell(std::move(text), nullptr), "note", std::move(note)); }

json row(json cells, const char* cls = nullptr) {
  return {{"class", cls ? json(cls) : json(nullptr)}, {"cells", std::move(cells)}};
}

json table(const char* cls, json head_cells, json rows, json note = nullptr) {
  return {{"class", cls ? json(cls) : json(nullptr)},
          {"head", head_cells.is_null() ? json(nullptr) : json{{"cells", std::move(head_cells)}}},
          {"rows", std::move(rows)},
          {"note", std::move(note)}};
}

json block(const char* kind, json value) { return {{kind, std::move(value)}}; }

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

json facts_table(const Index& index) {
  const json& r = *index.results;
  const size_t runs = member(r, "runs").size(), groups = member(r, "groups").size();
  auto fact = [](std::string name, json value) { return row({header_cell(std::move(name)), std::move(value)}); };
  return table("facts", nullptr,
               {fact("tool revision", code_cell(text_of(r, "tool_revision"))),
                fact("machine", cell(machine_summary(member(r, "machine")), nullptr)),
                fact("device", cell(text_of(r, "device"), nullptr)),
                fact("runs", cell(std::to_string(runs) + " runs in " + std::to_string(groups) + " groups over " +
                                      std::to_string(index.scenes.size()) + " scene(s)",
                                  nullptr))});
}

json references_table(const Index& index) {
  json rows = json::array();
  for (const Scene& scene : index.scenes) {
    for (const std::string& id : scene.references) {
      const json& ref = index.reference(id);
      rows.push_back(row({cell(scene_title(scene.name), nullptr), code_cell(id), cell(reference_summary(ref), nullptr),
                          cell(fmt(number(ref, "render_ms") / 1000.0) + " s")}));
    }
  }
  return table("refs", {head_cell("scene"), head_cell("reference"), head_cell("what"), head_cell("render time")}, rows);
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
json time_cell(const json& group, const std::vector<const json*>& runs) {
  double lo = kNaN, hi = kNaN;
  for (const json* r : runs) {
    const double mn = number(member(*r, "time_ms"), "min"), mx = number(member(*r, "time_ms"), "max");
    if (std::isfinite(mn)) lo = std::isfinite(lo) ? std::min(lo, mn) : mn;
    if (std::isfinite(mx)) hi = std::isfinite(hi) ? std::max(hi, mx) : mx;
  }
  double median = number(group, "time_ms_median");
  if (!std::isfinite(median)) median = mean_finite(run_values(runs, "time_ms", "median"));
  json c = cell(fmt(median));
  if (std::isfinite(lo) && std::isfinite(hi)) c["note"] = "[" + fmt(lo) + ".." + fmt(hi) + "]";
  return c;
}

// The spp rendered; a range when equal-time calibration gave the seeds different counts.
json spp_cell(const std::vector<const json*>& runs) {
  std::vector<double> spp = run_values(runs, nullptr, "spp");
  std::erase_if(spp, [](double v) { return !std::isfinite(v); });
  if (spp.empty()) return cell(kDash);
  const auto [lo, hi] = std::minmax_element(spp.begin(), spp.end());
  json c = cell(fmt_count(*lo) + (*lo == *hi ? "" : "\u2013" + fmt_count(*hi)));
  if (!runs.empty() && member(*runs.front(), "time_budget_ms").is_number())
    c["note"] = "(budget " + fmt(number(*runs.front(), "time_budget_ms")) + " ms)";
  return c;
}

json rmse_cell(const json& group) {
  const double std_dev = number(group, "rmse_std");
  return cell(fmt(number(group, "rmse_mean")) + (std::isfinite(std_dev) ? " \u00b1 " + fmt(std_dev, 2) : ""));
}

// The mean over the runs of their masked errors' `key` (reference "mask"; squared for "rmse": an
// MSE), NaN where no run has them.
double masked_mean(const std::vector<const json*>& runs, const char* key, bool squared) {
  std::vector<double> values;
  for (const json* r : runs) {
    const double v = number(member(member(*r, "metrics"), "masked"), key);
    values.push_back(squared ? v * v : v);
  }
  return mean_finite(values);
}

// Whether any of the runs has FLIP (results recorded before it have none): its columns are shown
// only then.
bool has_flip(const std::vector<const json*>& runs) {
  for (const json* r : runs)
    if (member(member(*r, "metrics"), "flip_ldr").is_number()) return true;
  return false;
}

json group_row(const Index& index, const json& g, const std::vector<std::string>& axes, bool masked, bool flip) {
  const std::vector<const json*> runs = index.runs_of(g);
  const bool pareto = member(g, "pareto") == true;
  double ssim = number(g, "ssim_mean");
  if (!std::isfinite(ssim)) ssim = mean_finite(run_values(runs, "metrics", "ssim"));
  json cells = {pareto ? with(cell("\u2605", "mark"), "title", "on the RMSE-vs-time Pareto front") : cell("", "mark"),
                cell(text_of(g, "label"), "label")};
  for (const std::string& a : axes) {
    const json& v = member(member(g, "axes"), a.c_str());
    cells.push_back(cell(v.is_null() ? kDash : text_of(v)));
  }
  for (json c : {spp_cell(runs), time_cell(g, runs), rmse_cell(g),
                 cell(fmt(mean_finite(run_values(runs, "metrics", "rel_mse"))))})
    cells.push_back(std::move(c));
  if (masked) {
    cells.push_back(cell(fmt(masked_mean(runs, "rmse", true))));
    cells.push_back(cell(fmt(masked_mean(runs, "rel_mse", false))));
  }
  cells.push_back(cell(fmt(mean_finite(run_values(runs, "metrics", "psnr")))));
  cells.push_back(cell(fmt(ssim)));
  if (flip)
    for (const char* key : {"flip_ldr_mean", "flip_hdr_mean"}) cells.push_back(cell(fmt(number(g, key))));
  for (json c : {cell(fmt(mean_finite(run_values(runs, nullptr, "efficiency")))),
                 cell(fmt(mean_finite(run_values(runs, nullptr, "ssim_gain_pct_per_ms")))),
                 cell(fmt(number(g, "bias2"))), cell(fmt(number(g, "variance"))), cell(std::to_string(runs.size()))})
    cells.push_back(std::move(c));
  return row(std::move(cells), pareto ? "pareto" : nullptr);
}

json group_table(const Index& index, const Scene& scene) {
  const std::vector<std::string> axes = axis_names(scene);
  json head = {with(head_cell("\u2605"), "title", "Pareto front"), head_cell("label")};
  for (const std::string& a : axes) head.push_back(head_cell(a));
  // Masked columns when a run of the scene was measured against an emitter mask.
  bool masked = false;
  for (const json* g : scene.groups)
    for (const json* r : index.runs_of(*g)) masked = masked || member(member(*r, "metrics"), "masked").is_object();
  for (json c : {head_cell("spp"), head_cell("time ms", "median [min..max]"), head_cell("RMSE", "mean \u00b1 std"),
                 head_cell("rel MSE")})
    head.push_back(std::move(c));
  if (masked) {
    head.push_back(head_cell("MSE masked", "pixels no visible emitter touches"));
    head.push_back(head_cell("rel MSE masked", "pixels no visible emitter touches"));
  }
  bool flip = false;
  for (const json* g : scene.groups) flip = flip || has_flip(index.runs_of(*g));
  head.push_back(head_cell("PSNR dB"));
  head.push_back(head_cell("SSIM"));
  if (flip) {
    head.push_back(head_cell("LDR-FLIP", "mean over pixels, 67 ppd"));
    head.push_back(head_cell("HDR-FLIP", "max over exposures"));
  }
  for (json c : {head_cell("efficiency 1/s"), head_cell("SSIM gain %/ms"), head_cell("bias\u00b2"), head_cell("variance"),
                 head_cell("seeds")})
    head.push_back(std::move(c));
  json rows = json::array();
  for (const json* g : scene.groups) rows.push_back(group_row(index, *g, axes, masked, flip));
  return table("groups", head, rows,
               "\u2605 on the RMSE-vs-time Pareto front of this scene. Time, RMSE, SSIM, bias\u00b2 and variance are "
               "over the group's seeds; rel MSE, PSNR, FLIP, efficiency and SSIM gain are means over its runs.");
}

// Sequences: per group (its seed-0 run), the medians over measured frames of the raw frames'
// error (before temporal reuse and denoising) and of the output's, and their flicker.
json sequence_table(const Index& index, const Scene& scene) {
  json rows = json::array();
  for (const json* g : scene.groups) {
    const json* run = representative_run(index, *g);
    if (!run || !member(*run, "frames").is_array()) continue;
    const json &raw = member(*run, "metrics_raw"), &out = member(*run, "metrics");
    rows.push_back(row({cell(text_of(*g, "label"), "label"), cell(fmt_count(number(*run, "warmup_frames"))),
                        cell(fmt_count(double(member(*run, "frames").size()))), cell(fmt(number(raw, "rmse"))),
                        cell(fmt(number(out, "rmse"))), cell(fmt(number(raw, "ssim"))), cell(fmt(number(out, "ssim"))),
                        cell(fmt(number(*run, "flicker_raw"))), cell(fmt(number(*run, "flicker")))}));
  }
  if (rows.empty()) return nullptr;
  json head = json::array();
  for (const char* h : {"label", "warm-up", "measured", "RMSE raw", "RMSE out", "SSIM raw", "SSIM out", "flicker raw",
                        "flicker out"})
    head.push_back(head_cell(h));
  return table("groups", head, rows,
               "Sequences: medians over the measured frames, each against its own reference; raw = the method's "
               "frames before temporal reuse and denoising, out = the output. Flicker: RMS of the frame-to-frame "
               "change minus the reference's (docs/sst-eval.md).");
}

// ---- plots

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

// RMSE per measured frame of each sequence group's seed-0 run, of the output or of the raw frames.
Plot per_frame_rmse_plot(const Index& index, const Scene& scene, bool raw) {
  std::vector<FrameSeries> series;
  int first = 0;
  for (const json* g : scene.groups) {
    const json* run = representative_run(index, *g);
    if (!run || !member(*run, "frames").is_array() || member(*run, "frames").empty()) continue;
    FrameSeries f{text_of(*g, "label"), {}, index.style(text_of(*g, "label"))};
    for (const json& frame : member(*run, "frames")) f.values.push_back(number(member(frame, raw ? "metrics_raw" : "metrics"), "rmse"));
    first = int(number(member(*run, "frames")[0], "index"));
    series.push_back(std::move(f));
  }
  PlotAxis y;
  y.label = raw ? "RMSE of the raw frame" : "RMSE of the output";
  y.scale = AxisScale::log10;
  return per_frame_plot(raw ? "raw frames: RMSE per frame" : "output: RMSE per frame", y, series, first);
}

// The scene's plots, each left out when it would have fewer than 2 points.
json plot_views(const Index& index, const Scene& scene) {
  std::vector<Plot> plots{rmse_time_plot(index, scene)};
  if (vpls_vary(scene)) plots.insert(plots.end(), {vpl_plot(index, scene, true), vpl_plot(index, scene, false)});
  plots.insert(plots.end(), {per_frame_rmse_plot(index, scene, false), per_frame_rmse_plot(index, scene, true)});
  json views = json::array();
  for (const Plot& plot : plots)
    if (drawable_point_count(plot) >= 2) views.push_back(plot_view(plot));
  return views;
}

// ---- image comparison

// The pane keeps the image's aspect ratio so that zooming scrolls inside it instead of growing it.
json aspect_of(const json& run) {
  const double w = number(member(run, "params"), "width"), h = number(member(run, "params"), "height");
  if (!(w > 0 && h > 0)) return nullptr;
  return fmt_count(w) + " / " + fmt_count(h);
}

json reference_card(const Index& index, const std::string& id, const json& aspect) {
  const json& ref = index.reference(id);
  return {{"reference", true},
          {"heading", {span("reference "), span(id, true)}},
          {"axes", nullptr},
          {"sub", {span(reference_summary(ref))}},
          {"figures", {image_figure(text_of(ref, "image_png"), "reference", "reference", aspect)}}};
}

json run_card(const Index& index, const json& group, const json& run) {
  const json& images = member(run, "images");
  const std::string id = text_of(run, "id"), png = text_of(images, "png");
  const json aspect = aspect_of(run);
  json flip = image_figure(png, "run " + id, nullptr, aspect);
  flip["flip"] = {{"run", url(png)}, {"ref", url(text_of(index.reference(text_of(run, "reference")), "image_png"))},
                  {"id", id}};
  // json::array, not {flip}: clang copies a one-element brace list of a json (CWG 2137), GCC
  // makes it an array.
  json figures = json::array({flip});
  // A sequence: its measured frames beside their references, playing in step.
  const json& videos = member(run, "videos");
  if (!text_of(videos, "frame").empty()) figures.push_back(video_figure(text_of(videos, "frame"), "sequence", aspect));
  if (!text_of(videos, "reference").empty())
    figures.push_back(video_figure(text_of(videos, "reference"), "its reference", aspect));
  // A pruned results folder keeps no heat maps (sst-eval sweep writes them; prune_results.sh drops them).
  if (!text_of(images, "error_png").empty()) {
    json error = image_figure(text_of(images, "error_png"), "error of " + id,
                              "relative error, 0 (black) .. \u22651 (yellow)", aspect);
    error["ramp"] = true;
    figures.push_back(error);
  }
  const std::string axes = axes_text(member(group, "axes"));
  return {{"reference", false},
          {"heading", {span(text_of(group, "label"))}},
          {"axes", axes.empty() ? json(nullptr) : json(axes)},
          {"sub",
           {span("run "), span(id, true),
            span(" (seed " + text_of(run, "seed") + "), RMSE " + fmt(number(member(run, "metrics"), "rmse")) +
                 ", SSIM " + fmt(number(member(run, "metrics"), "ssim")) +
                 (has_flip({&run}) ? ", LDR-FLIP " + fmt(number(member(run, "metrics"), "flip_ldr")) : std::string()) +
                 ", " + fmt(number(member(run, "time_ms"), "median")) + " ms")}},
          {"figures", figures}};
}

json image_grid(const Index& index, const Scene& scene) {
  json cards = json::array();
  const json aspect = scene.runs.empty() ? json(nullptr) : aspect_of(*scene.runs.front());
  for (const std::string& id : scene.references) cards.push_back(reference_card(index, id, aspect));
  for (const json* g : scene.groups)
    if (const json* run = representative_run(index, *g)) cards.push_back(run_card(index, *g, *run));
  if (cards.empty()) return nullptr;
  return {{"note", "one run per group (seed 0); click an image to flip it with its reference; the panes scroll together"},
          {"cards", cards}};
}

// ---- scene section, runs table, page

json scene_section(const Index& index, const Scene& scene) {
  json blocks = json::array();
  for (const std::string& id : scene.references)
    blocks.push_back(block("paragraph", {{"spans",
                                          {span("metrics against reference "), span(id, true),
                                           span(": " + reference_summary(index.reference(id)))}}}));
  if (!scene.groups.empty()) blocks.push_back(block("table", group_table(index, scene)));
  if (json sequences = sequence_table(index, scene); !sequences.is_null()) blocks.push_back(block("table", sequences));
  json plots = plot_views(index, scene);
  if (!plots.empty()) blocks.push_back(block("plots", {{"items", plots}}));
  blocks.push_back(block("heading", "Images"));
  if (json grid = image_grid(index, scene); !grid.is_null()) blocks.push_back(block("images", grid));
  return {{"name", scene_title(scene.name)}, {"blocks", blocks}};
}

json runs_details(const Index& index) {
  const json& runs = member(*index.results, "runs");
  std::vector<const json*> all;
  for (const json& r : runs) all.push_back(&r);
  const bool flip = has_flip(all);
  json rows = json::array();
  for (const json& r : runs) {
    json cells = {code_cell(text_of(r, "id"), "id"), cell(text_of(r, "label"), "label"),
                  cell(scene_title(text_of(r, "scene")), "label"), cell(text_of(r, "seed")),
                  cell(text_of(r, "spp")), cell(fmt(number(member(r, "time_ms"), "median"))),
                  cell(fmt(number(member(r, "metrics"), "rmse"))),
                  cell(fmt(number(member(r, "metrics"), "ssim")))};
    if (flip)
      for (const char* key : {"flip_ldr", "flip_hdr"}) cells.push_back(cell(fmt(number(member(r, "metrics"), key))));
    rows.push_back(row(std::move(cells)));
  }
  json head = json::array();
  for (const char* name : {"id", "label", "scene", "seed", "spp", "time ms", "RMSE", "SSIM"}) head.push_back(head_cell(name));
  if (flip)
    for (const char* name : {"LDR-FLIP", "HDR-FLIP"}) head.push_back(head_cell(name));
  return {{"summary", "All " + std::to_string(runs.size()) + " runs"}, {"table", table(nullptr, head, rows)}};
}

}  // namespace

nlohmann::json image_figure(std::string_view path, std::string alt, nlohmann::json caption, nlohmann::json aspect) {
  return {{"src", url(path)}, {"video", nullptr}, {"link", nullptr}, {"alt", std::move(alt)},
          {"caption", std::move(caption)}, {"ramp", false}, {"flip", nullptr}, {"aspect", std::move(aspect)}};
}

nlohmann::json video_figure(std::string_view path, nlohmann::json caption, nlohmann::json aspect) {
  json figure = image_figure("", "", std::move(caption), std::move(aspect));
  figure["src"] = nullptr;
  figure["video"] = url(path);
  return figure;
}

nlohmann::json report_view(const nlohmann::json& results) {
  const Index index = build_index(results);
  json sections = json::array();
  for (const Scene& scene : index.scenes) sections.push_back(scene_section(index, scene));
  return {{"title", "sst-eval report: " + text_of(results, "name")},
          {"facts", facts_table(index)},
          {"references", references_table(index)},
          {"sections", sections},
          {"runs", runs_details(index)}};
}

std::string render_report(const nlohmann::json& view) { return render_page_template("report.html", view); }

std::string make_report_html(const nlohmann::json& results) { return render_report(report_view(results)); }

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
