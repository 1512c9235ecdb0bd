#include "core/eval/table.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "core/eval/json_fields.h"
#include "core/util/error.h"

namespace sst {
namespace {

std::string fixed(double v, int significant = 4) {
  if (!std::isfinite(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", significant, v);
  return text;
}

std::string cell(const nlohmann::json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

using Row = std::vector<std::string>;

// Mean over the group's runs of a value picked from each run record.
template <class F>
double group_mean(const nlohmann::json& group, const std::map<std::string, const nlohmann::json*>& runs, F pick) {
  double sum = 0.0;
  int n = 0;
  for (const auto& id : group["runs"]) {
    double v = pick(*runs.at(id.get<std::string>()));
    if (std::isfinite(v)) sum += v, ++n;
  }
  return n ? sum / n : NAN;
}

Row group_row(const nlohmann::json& g, const std::map<std::string, const nlohmann::json*>& runs, bool scenes,
              const std::vector<std::string>& axes, const std::vector<std::string>& stages, bool masked, bool flip) {
  Row row;
  if (scenes) row.push_back(g["scene"].get<std::string>());
  row.push_back(g["label"].get<std::string>());
  for (const std::string& a : axes) row.push_back(g["axes"].contains(a) ? cell(g["axes"][a]) : "");
  row.push_back(cell(g["spp"]));
  double tmin = INFINITY, tmax = 0.0;
  for (const auto& id : g["runs"]) {
    tmin = std::min(tmin, (*runs.at(id))["time_ms"]["min"].get<double>());
    tmax = std::max(tmax, (*runs.at(id))["time_ms"]["max"].get<double>());
  }
  row.push_back(fixed(number(g["time_ms_median"])) + " [" + fixed(tmin, 3) + "-" + fixed(tmax, 3) + "]");
  for (const std::string& s : stages)
    row.push_back(fixed(group_mean(g, runs, [&](const nlohmann::json& r) {
      return r["stages"].contains(s) ? number(r["stages"][s]["median"]) : NAN;
    })));
  std::string rmse = fixed(number(g["rmse_mean"]));
  if (g["rmse_std"].is_number()) rmse += " ± " + fixed(number(g["rmse_std"]), 2);
  row.push_back(rmse);
  row.push_back(fixed(group_mean(g, runs, [](const nlohmann::json& r) { return number(r["metrics"]["rel_mse"]); })));
  if (masked) {
    // MSE: the mean over the runs of their squared masked RMSE.
    row.push_back(fixed(group_mean(g, runs, [](const nlohmann::json& r) {
      const double v = number(member(member(r, "metrics"), "masked"), "rmse");
      return v * v;
    })));
    row.push_back(fixed(group_mean(g, runs, [](const nlohmann::json& r) {
      return number(member(member(r, "metrics"), "masked"), "rel_mse");
    })));
  }
  row.push_back(fixed(number(g["ssim_mean"])));
  if (flip)
    for (const char* key : {"flip_ldr_mean", "flip_hdr_mean"}) row.push_back(fixed(number(g, key)));
  row.push_back(fixed(group_mean(g, runs, [](const nlohmann::json& r) { return number(r["ssim_gain_pct_per_ms"]); }), 3));
  row.push_back(g.value("pareto", false) ? "yes" : "");
  return row;
}

std::string markdown(const Row& header, const std::vector<Row>& rows) {
  std::ostringstream out;
  auto line = [&](const Row& r) {
    out << "|";
    for (const std::string& c : r) out << " " << c << " |";
    out << "\n";
  };
  line(header);
  out << "|";
  for (size_t i = 0; i < header.size(); ++i) out << "---|";
  out << "\n";
  for (const Row& r : rows) line(r);
  return out.str();
}

std::string csv(const Row& header, const std::vector<Row>& rows) {
  std::ostringstream out;
  auto line = [&](const Row& r) {
    for (size_t i = 0; i < r.size(); ++i) {
      bool quote = r[i].find_first_of(",\"") != std::string::npos;
      out << (i ? "," : "") << (quote ? "\"" : "") << r[i] << (quote ? "\"" : "");
    }
    out << "\n";
  };
  line(header);
  for (const Row& r : rows) line(r);
  return out.str();
}

}  // namespace

std::string format_table(const nlohmann::json& results, const std::string& format, const std::vector<std::string>& stages) {
  if (format != "markdown" && format != "csv") throw Error("table: unknown format '" + format + "' (markdown or csv)");
  std::map<std::string, const nlohmann::json*> runs;
  for (const nlohmann::json& r : results.at("runs")) runs[r["id"]] = &r;
  std::set<std::string> scene_names;
  std::vector<std::string> axes;
  for (const nlohmann::json& g : results.at("groups")) {
    scene_names.insert(g["scene"].get<std::string>());
    for (const auto& [key, value] : g["axes"].items())
      if (key != "spp" && key != "method" && std::find(axes.begin(), axes.end(), key) == axes.end()) axes.push_back(key);
  }
  bool scenes = scene_names.size() > 1;
  // Masked columns when any run was measured against an emitter mask (reference "mask").
  bool masked = false;
  for (const nlohmann::json& r : results.at("runs")) masked = masked || (r.contains("metrics") && r["metrics"].contains("masked"));
  // FLIP columns when any run has FLIP (results recorded before it have none).
  bool flip = false;
  for (const nlohmann::json& r : results.at("runs")) flip = flip || member(member(r, "metrics"), "flip_ldr").is_number();
  Row header;
  if (scenes) header.push_back("scene");
  header.push_back("method");  // the label: the method, or the variant's name (with the method if it is an axis)
  header.insert(header.end(), axes.begin(), axes.end());
  header.push_back("spp");
  header.push_back("frame ms (median [min-max])");
  for (const std::string& s : stages) header.push_back(s + " ms");
  header.push_back("RMSE");
  header.push_back("relMSE");
  if (masked) {
    header.push_back("MSE masked");
    header.push_back("relMSE masked");
  }
  header.push_back("SSIM");
  if (flip) {
    header.push_back("LDR-FLIP");
    header.push_back("HDR-FLIP");
  }
  for (const char* h : {"gain %SSIM/ms", "Pareto"}) header.push_back(h);
  std::vector<Row> rows;
  for (const nlohmann::json& g : results["groups"]) rows.push_back(group_row(g, runs, scenes, axes, stages, masked, flip));
  return format == "markdown" ? markdown(header, rows) : csv(header, rows);
}

}  // namespace sst
