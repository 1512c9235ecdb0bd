#include "core/eval/results.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/eval/json_fields.h"
#include "core/eval/report.h"
#include "core/image/image.h"
#include "core/util/json_io.h"
#include "core/util/machine_info.h"
#include "core/util/statistics.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

double median_time(const nlohmann::json& run) { return run["time_ms"]["median"].get<double>(); }

// Runs compared with each other for gain and Pareto front: one scene, one kind of reference,
// one material model (diffuse-only renders have their own reference).
std::string comparison_set(const nlohmann::json& run) {
  bool diffuse = run["params"].value("diffuse_only", false);
  return run["scene"].get<std::string>() + "|" + run["reference_description"].value("kind", "") + "|" +
         (diffuse ? "diffuse" : "full");
}

// The SST paper's gain (Table 1): the relative SSIM increase per invested ms over the
// lowest-quality run of the comparison set.
void add_efficiency_and_gain(std::vector<nlohmann::json>& runs) {
  std::map<std::string, const nlohmann::json*> base;
  for (const nlohmann::json& r : runs) {
    const nlohmann::json*& b = base[comparison_set(r)];
    if (!b || number(r["metrics"]["ssim"], 2.0) < number((*b)["metrics"]["ssim"], 2.0)) b = &r;
  }
  std::map<std::string, std::pair<std::string, std::pair<double, double>>> base_values;
  for (const auto& [set, b] : base)
    base_values[set] = {(*b)["id"], {number((*b)["metrics"]["ssim"]), median_time(*b)}};
  for (nlohmann::json& r : runs) {
    double rmse = number(r["metrics"]["rmse"]), t = median_time(r);
    r["efficiency"] = number_or_null(1.0 / (rmse * rmse * t / 1000.0));
    const auto& [base_id, values] = base_values[comparison_set(r)];
    auto [ssim_b, t_b] = values;
    double ssim = number(r["metrics"]["ssim"]);
    r["gain_base"] = base_id;
    r["ssim_gain_pct_per_ms"] = (r["id"] != base_id && t > t_b)
                                    ? number_or_null(100.0 * (ssim - ssim_b) / ssim_b / (t - t_b))
                                    : nlohmann::json(nullptr);
  }
}

// Bias^2 and variance per pixel and channel of one run's error over seeds: with d_s = image_s -
// reference_s, variance = mean of the unbiased sample variance of d, and bias^2 = mean(dbar^2) -
// variance / n (the expected excess of the sample mean's square), floored at 0.
std::pair<double, double> bias_and_variance(const std::vector<const nlohmann::json*>& runs, const std::string& dir) {
  size_t n = runs.size();
  std::vector<double> sum, sum2;
  for (const nlohmann::json* r : runs) {
    Image img = read_image((fs::path(dir) / (*r)["images"]["exr"].get<std::string>()).string());
    Image ref = read_image((fs::path(dir) / "references" / ((*r)["reference"].get<std::string>() + ".exr")).string());
    if (sum.empty()) sum.assign(img.data.size(), 0.0), sum2.assign(img.data.size(), 0.0);
    for (size_t i = 0; i < img.data.size(); ++i) {
      double d = double(img.data[i]) - double(ref.data[i]);
      if (!std::isfinite(d)) d = 0.0;
      sum[i] += d;
      sum2[i] += d * d;
    }
  }
  double variance = 0.0, mean2 = 0.0;
  for (size_t i = 0; i < sum.size(); ++i) {
    double mean = sum[i] / double(n);
    variance += std::max(sum2[i] - double(n) * mean * mean, 0.0) / double(n - 1);
    mean2 += mean * mean;
  }
  variance /= double(sum.size());
  mean2 /= double(sum.size());
  return {std::max(mean2 - variance / double(n), 0.0), variance};
}

// A metric over the seeds of one sweep point: mean and sample std, and the robust pair the CI
// check uses (median, and 1.4826 x the median absolute deviation, which estimates the std of a
// normal distribution but ignores a seed hit by a rare firefly). Stds are NaN for one seed.
void add_seed_statistics(nlohmann::json& group, const std::string& name, const std::vector<double>& v) {
  double mean = 0.0, s = 0.0;
  for (double x : v) mean += x / double(v.size());
  for (double x : v) s += (x - mean) * (x - mean);
  double mid = median(v);
  std::vector<double> deviations;
  for (double x : v) deviations.push_back(std::abs(x - mid));
  bool several = v.size() > 1;
  group[name + "_mean"] = number_or_null(mean);
  group[name + "_std"] = number_or_null(several ? std::sqrt(s / double(v.size() - 1)) : NAN);
  group[name + "_median"] = number_or_null(mid);
  group[name + "_robust_std"] = number_or_null(several ? 1.4826 * median(deviations) : NAN);
}

// A metric that runs recorded before it lack (FLIP): statistics over the runs that have it, and
// nulls when none has.
void add_optional_statistics(nlohmann::json& group, const std::string& name, std::vector<double> v) {
  std::erase_if(v, [](double x) { return !std::isfinite(x); });
  if (!v.empty()) return add_seed_statistics(group, name, v);
  for (const char* suffix : {"_mean", "_std", "_median", "_robust_std"}) group[name + suffix] = nullptr;
}

nlohmann::json make_group(const std::string& name, const std::vector<const nlohmann::json*>& runs, const std::string& dir) {
  const nlohmann::json& first = *runs.front();
  std::vector<double> times, rmse, ssim, flip_ldr, flip_hdr;
  nlohmann::json ids = nlohmann::json::array();
  for (const nlohmann::json* r : runs) {
    ids.push_back((*r)["id"]);
    times.push_back(median_time(*r));
    rmse.push_back(number((*r)["metrics"]["rmse"]));
    ssim.push_back(number((*r)["metrics"]["ssim"]));
    flip_ldr.push_back(number(member((*r)["metrics"], "flip_ldr")));
    flip_hdr.push_back(number(member((*r)["metrics"], "flip_hdr")));
  }
  size_t n = runs.size();
  nlohmann::json g = {{"group", name},           {"label", first["label"]},     {"scene", first["scene"]},
                      {"method", first["method"]}, {"variant", first["variant"]}, {"axes", first["axes"]},
                      {"spp", first["spp"]},     {"runs", ids},                 {"seeds", n},
                      {"time_ms_median", median(times)}, {"bias2", nullptr}, {"variance", nullptr},
                      {"comparison_set", comparison_set(first)}};
  add_seed_statistics(g, "rmse", rmse);
  add_seed_statistics(g, "ssim", ssim);
  add_optional_statistics(g, "flip_ldr", flip_ldr);
  add_optional_statistics(g, "flip_hdr", flip_hdr);
  bool images_present = std::all_of(runs.begin(), runs.end(), [&](const nlohmann::json* r) {
    return fs::exists(fs::path(dir) / (*r)["images"]["exr"].get<std::string>()) &&
           fs::exists(fs::path(dir) / "references" / ((*r)["reference"].get<std::string>() + ".exr"));
  });
  if (n > 1 && images_present) {
    auto [bias2, variance] = bias_and_variance(runs, dir);
    g["bias2"] = bias2;
    g["variance"] = variance;
  }
  return g;
}

void mark_pareto(nlohmann::json& groups) {
  for (nlohmann::json& g : groups) {
    double t = g["time_ms_median"].get<double>(), e = number(g["rmse_mean"], INFINITY);
    bool dominated = false;
    for (const nlohmann::json& o : groups) {
      if (&o == &g || o["comparison_set"] != g["comparison_set"]) continue;
      double to = o["time_ms_median"].get<double>(), eo = number(o["rmse_mean"], INFINITY);
      if (to <= t && eo <= e && (to < t || eo < e)) dominated = true;
    }
    g["pareto"] = !dominated && std::isfinite(e);
  }
}

std::string csv_field(const nlohmann::json& v) {
  if (v.is_null()) return "";
  std::string s = v.is_string() ? v.get<std::string>() : v.dump();
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

nlohmann::json assemble_results(const ExperimentConfig& config, std::vector<nlohmann::json> runs,
                                const std::string& results_dir) {
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a["index"] < b["index"]; });
  add_efficiency_and_gain(runs);
  // What each scene requires is the same for all its runs: kept once, per scene.
  nlohmann::json scenes = nlohmann::json::object();
  for (nlohmann::json& r : runs) {
    std::string key = r["scene"].get<std::string>() + (r["params"].value("diffuse_only", false) ? " diffuse_only" : "");
    if (r.contains("scene_summary")) scenes[key] = r["scene_summary"];
    r.erase("scene_summary");
  }
  nlohmann::json references = nlohmann::json::object();
  for (const nlohmann::json& r : runs) {
    nlohmann::json ref = r["reference_description"];
    ref["image_png"] = "references/" + r["reference"].get<std::string>() + ".png";
    references[r["reference"].get<std::string>()] = ref;
  }
  std::vector<std::string> order;
  std::map<std::string, std::vector<const nlohmann::json*>> members;
  for (const nlohmann::json& r : runs) {
    std::string g = r["group"];
    if (!members.count(g)) order.push_back(g);
    members[g].push_back(&r);
  }
  nlohmann::json groups = nlohmann::json::array();
  for (const std::string& g : order) groups.push_back(make_group(g, members[g], results_dir));
  mark_pareto(groups);
  return {{"schema_version", kResultsSchemaVersion},
          {"tool", "sst-eval"},
          {"tool_revision", tool_revision()},
          {"machine", machine_info()},
          {"device", runs.empty() ? nlohmann::json(nullptr) : runs.front().value("device", nlohmann::json(nullptr))},
          {"name", config.name},
          {"description", config.description},
          {"config", config.source},
          {"scenes", scenes},
          {"references", references},
          {"runs", runs},
          {"groups", groups}};
}

std::string results_csv(const nlohmann::json& results) {
  std::set<std::string> axis_names;
  for (const nlohmann::json& r : results["runs"])
    for (const auto& [key, value] : r["axes"].items())
      if (key != "method" && key != "seed" && key != "spp") axis_names.insert(key);  // columns already
  std::ostringstream out;
  out << "id,index,scene,label,method,variant,seed";
  for (const std::string& a : axis_names) out << "," << a;
  out << ",spp,time_budget_ms,time_ms_median,time_ms_min,time_ms_max,rmse,rel_mse,psnr,ssim,efficiency,"
         "ssim_gain_pct_per_ms,reference,flip_ldr,flip_hdr\n";
  for (const nlohmann::json& r : results["runs"]) {
    out << csv_field(r["id"]) << "," << r["index"] << "," << csv_field(r["scene"]) << "," << csv_field(r["label"]) << ","
        << csv_field(r["method"]) << "," << csv_field(r["variant"]) << "," << r["seed"];
    for (const std::string& a : axis_names) out << "," << csv_field(r["axes"].value(a, nlohmann::json(nullptr)));
    const nlohmann::json& m = r["metrics"];
    out << "," << r["spp"] << "," << csv_field(r["time_budget_ms"]) << "," << r["time_ms"]["median"] << ","
        << r["time_ms"]["min"] << "," << r["time_ms"]["max"] << "," << csv_field(m["rmse"]) << ","
        << csv_field(m["rel_mse"]) << "," << csv_field(m["psnr"]) << "," << csv_field(m["ssim"]) << ","
        << csv_field(r["efficiency"]) << "," << csv_field(r["ssim_gain_pct_per_ms"]) << "," << csv_field(r["reference"])
        << "," << csv_field(member(m, "flip_ldr")) << "," << csv_field(member(m, "flip_hdr")) << "\n";
  }
  return out.str();
}

void write_results(const nlohmann::json& results, const std::string& dir) {
  write_json_atomic((fs::path(dir) / "results.json").string(), results);
  write_text_atomic((fs::path(dir) / "results.csv").string(), results_csv(results));
  write_report(results, dir);
}

}  // namespace sst
