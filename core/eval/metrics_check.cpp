#include "core/eval/metrics_check.h"

#include <cmath>
#include <map>
#include <sstream>

#include "core/eval/json_fields.h"
#include "core/util/json_io.h"

namespace sst {
namespace {

std::string fmt(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.5g", v);
  return std::isfinite(v) ? text : "-";
}

struct Comparison {
  std::string status;  // "ok", "WORSE", "better"
  double tolerance;
};

// `badness`: how bad a value is (rmse itself, 1 - ssim), so "worse" is always "larger".
Comparison compare(double base, double fresh, double std_over_seeds, int seeds, int fresh_seeds, const CheckParams& p) {
  // The median of n normal values has a standard error of about 1.2533 sigma / sqrt(n); the
  // baseline usually has more seeds than a check renders.
  double noise = std::isfinite(std_over_seeds) && seeds > 1
                     ? p.sigmas * 1.2533 * std_over_seeds * std::sqrt(1.0 / seeds + 1.0 / std::max(fresh_seeds, 1))
                     : 0.0;
  double tolerance = std::max(noise, p.min_relative * std::abs(base));
  if (!std::isfinite(fresh) && std::isfinite(base)) return {"WORSE", tolerance};
  if (fresh - base > tolerance) return {"WORSE", tolerance};
  if (base - fresh > tolerance) return {"better", tolerance};
  return {"ok", tolerance};
}

std::string change(double base, double fresh) {
  if (!(std::abs(base) > 0.0) || !std::isfinite(fresh)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f%%", 100.0 * (fresh - base) / base);
  return text;
}

}  // namespace

CheckOutcome check_against_baseline(const nlohmann::json& fresh, const nlohmann::json& baseline, const CheckParams& p) {
  CheckOutcome out;
  std::map<std::string, const nlohmann::json*> groups;
  for (const nlohmann::json& g : fresh.at("groups")) groups[g["group"]] = &g;
  std::map<std::string, size_t> nonfinite;
  for (const nlohmann::json& r : fresh.at("runs")) nonfinite[r["group"]] += r["metrics"].value("nonfinite_test", size_t(0));
  std::ostringstream t;
  t << "| group | metric | baseline | fresh | change | tolerance | status | time ms baseline -> fresh |\n"
    << "|---|---|---|---|---|---|---|---|\n";
  auto fail = [&] { ++out.failures, out.passed = false; };
  for (const nlohmann::json& b : baseline.at("groups")) {
    std::string name = b["group"];
    auto it = groups.find(name);
    if (it == groups.end()) {
      t << "| " << name << " | - | - | missing | - | - | WORSE | - |\n";
      fail();
      continue;
    }
    const nlohmann::json& f = *it->second;
    int seeds = b.value("seeds", 1);
    int fresh_seeds = f.value("seeds", seeds);
    std::string times = fmt(number(b, "time_ms_median")) + " -> " + fmt(number(f, "time_ms_median"));
    double rmse_b = number(b, "rmse_median"), rmse_f = number(f, "rmse_median");
    // SSIM: compare 1 - ssim, the dissimilarity, so that the relative floor scales with the error.
    double dssim_b = 1.0 - number(b, "ssim_median"), dssim_f = 1.0 - number(f, "ssim_median");
    Comparison rmse = compare(rmse_b, rmse_f, number(b, "rmse_robust_std"), seeds, fresh_seeds, p);
    Comparison ssim = compare(dssim_b, dssim_f, number(b, "ssim_robust_std"), seeds, fresh_seeds, p);
    t << "| " << name << " | rmse | " << fmt(rmse_b) << " | " << fmt(rmse_f) << " | " << change(rmse_b, rmse_f) << " | "
      << fmt(rmse.tolerance) << " | " << rmse.status << " | " << times << " |\n";
    t << "| " << name << " | 1-ssim | " << fmt(dssim_b) << " | " << fmt(dssim_f) << " | " << change(dssim_b, dssim_f)
      << " | " << fmt(ssim.tolerance) << " | " << ssim.status << " | |\n";
    for (const char* metric : {"flip_ldr", "flip_hdr"}) {
      const std::string key = std::string(metric) + "_median";
      const double flip_b = number(b, key.c_str()), flip_f = number(f, key.c_str());
      t << "| " << name << " | " << metric << " | " << fmt(flip_b) << " | " << fmt(flip_f) << " | "
        << change(flip_b, flip_f) << " | - | recorded | |\n";
      out.flip[name][metric] = {{"baseline", number_or_null(flip_b)}, {"fresh", number_or_null(flip_f)}};
    }
    if (rmse.status == "WORSE") fail();
    if (ssim.status == "WORSE") fail();
    if (nonfinite[name] > 0) {
      t << "| " << name << " | non-finite pixels | 0 | " << nonfinite[name] << " | - | 0 | WORSE | |\n";
      fail();
    }
    groups.erase(it);
  }
  for (const auto& [name, g] : groups) t << "| " << name << " | - | not in baseline | new | - | - | ok | |\n";
  out.table = t.str();
  return out;
}

}  // namespace sst
