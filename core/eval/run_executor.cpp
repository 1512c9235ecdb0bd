#include "core/eval/run_executor.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/metrics/metrics.h"
#include "core/pipeline/render_record.h"
#include "core/scene/scene_summary.h"
#include "core/util/json_io.h"
#include "core/util/params.h"
#include "core/util/statistics.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

constexpr int kMaxCalibratedSpp = 1 << 16;

RenderResult render_run(const Scene& scene, const RunSpec& run, int spp) {
  RenderOptions options;
  params_from_json(options, run.options, "run " + run.id);
  if (spp > 0) options.spp = spp;
  return render_frame(scene, options, run.method_params, true);
}

// One correction of the calibrated spp when the measured median misses the budget by more than
// 10%: the per-spp cost is re-estimated from the measurement itself.
int refine_spp(int spp, double measured_ms, double budget_ms, nlohmann::json& calibration) {
  calibration["first_spp"] = spp;
  calibration["first_frame_ms"] = measured_ms;
  if (std::abs(measured_ms - budget_ms) <= 0.1 * budget_ms) return spp;
  double fixed = calibration["fixed_ms"].get<double>();
  double per_spp = std::max((measured_ms - fixed) / spp, 1e-6);
  return int(std::clamp(std::round((budget_ms - fixed) / per_spp), 1.0, double(kMaxCalibratedSpp)));
}

}  // namespace

int calibrate_spp(const Scene& scene, const RunSpec& run, double budget_ms, nlohmann::json* probes) {
  const int spp_a = 1, spp_b = 4;
  // The faster of two renders per probe: timing noise only ever adds time.
  auto probe = [&](int spp) { return std::min(frame_ms(render_run(scene, run, spp)), frame_ms(render_run(scene, run, spp))); };
  double t_a = probe(spp_a);
  double t_b = probe(spp_b);
  double per_spp = std::max((t_b - t_a) / (spp_b - spp_a), 1e-6);
  double fixed = std::max(t_a - per_spp * spp_a, 0.0);
  double spp = std::round((budget_ms - fixed) / per_spp);
  int result = int(std::clamp(spp, 1.0, double(kMaxCalibratedSpp)));
  if (probes) *probes = {{"spp", {spp_a, spp_b}}, {"frame_ms", {t_a, t_b}}, {"fixed_ms", fixed}, {"per_spp_ms", per_spp}};
  return result;
}

nlohmann::json execute_run(const Scene& scene, const RunSpec& run, const RunReference& reference,
                           const std::string& run_dir) {
  nlohmann::json calibration = nullptr;
  int spp = run.time_budget_ms > 0.0 ? calibrate_spp(scene, run, run.time_budget_ms, &calibration) : 0;
  std::vector<RenderResult> renders;
  std::vector<double> frame_times;
  auto render_repeats = [&] {
    renders.clear();
    frame_times.clear();
    for (int i = 0; i < run.repeat; ++i) {
      renders.push_back(render_run(scene, run, spp));
      frame_times.push_back(frame_ms(renders.back()));
    }
  };
  render_repeats();
  if (run.time_budget_ms > 0.0) {
    int refined = refine_spp(spp, median(frame_times), run.time_budget_ms, calibration);
    if (refined != spp) spp = refined, render_repeats();
  }
  const RenderResult& last = renders.back();
  std::vector<StageTimer> timers;
  for (const RenderResult& r : renders) timers.push_back(r.timer);

  fs::path dir(run_dir);
  write_image((dir / "image.exr").string(), last.frame.color, last.frame.layers());
  write_image((dir / "image.png").string(), last.frame.color, {}, last.options.exposure);
  write_image((dir / "error.png").string(), error_heatmap(last.frame.color, *reference.image));
  ImageMetrics metrics = compare_images(last.frame.color, *reference.image);

  nlohmann::json params = params_to_json(last.options);
  params.update(last.method_params);
  nlohmann::json record = {
      {"id", run.id},
      {"index", run.index},
      {"group", run.group},
      {"label", run.label},
      {"scene", run.scene},
      {"scene_source", scene.source},
      {"method", last.options.method},
      {"variant", run.variant},
      {"axes", run.axes},
      {"seed", run.seed},
      {"params", params},
      {"reference", reference.id},
      {"reference_description", reference.description},
      {"time_budget_ms", run.time_budget_ms > 0.0 ? nlohmann::json(run.time_budget_ms) : nlohmann::json(nullptr)},
      {"calibration", calibration},
      {"spp", last.options.spp},
      {"repeat", run.repeat},
      {"time_ms", median_min_max(frame_times)},
      {"stages", stage_statistics(timers)},
      {"counters", last.frame.counters.to_json(frame_ms(last))},
      {"device", last.device},
      {"scene_summary", scene_summary(scene, last.options.diffuse_only)},
      {"metrics", to_json(metrics)},
      {"images",
       {{"exr", "runs/" + run.id + "/image.exr"}, {"png", "runs/" + run.id + "/image.png"}, {"error_png", "runs/" + run.id + "/error.png"}}},
      {"spec_hash", run.spec_hash},
  };
  record["counters"]["method"] = last.frame.method_counters;
  write_json_atomic((dir / "run.json").string(), record);
  return record;
}

}  // namespace sst
