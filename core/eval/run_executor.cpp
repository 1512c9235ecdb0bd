#include "core/eval/run_executor.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "core/eval/sequence_checkpoint.h"
#include "core/pipeline/method_registry.h"
#include "core/image/video.h"
#include "core/metrics/error_map.h"
#include "core/metrics/flip.h"
#include "core/metrics/metrics.h"
#include "core/pipeline/render_record.h"
#include "core/pipeline/sequence.h"
#include "core/scene/key_frame_path.h"
#include "core/scene/scene_summary.h"
#include "core/util/json_io.h"
#include "core/util/params.h"
#include "core/util/error.h"
#include "core/util/statistics.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

constexpr int kMaxCalibratedSpp = 1 << 16;

RenderOptions run_options(const RunSpec& run);

RenderResult render_run(const Scene& scene, const RunSpec& run, int spp) {
  RenderOptions options = run_options(run);
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

// The spp whose frame time meets `budget_ms` under the linear model t = fixed + per_spp * spp
// through two probes: `t_a` ms at kProbeSpp[0] and `t_b` at kProbeSpp[1]. `calibration` receives
// the model.
constexpr int kProbeSpp[2] = {1, 4};
int spp_for_budget(double t_a, double t_b, double budget_ms, nlohmann::json& calibration) {
  double per_spp = std::max((t_b - t_a) / (kProbeSpp[1] - kProbeSpp[0]), 1e-6);
  double fixed = std::max(t_a - per_spp * kProbeSpp[0], 0.0);
  calibration = {{"spp", {kProbeSpp[0], kProbeSpp[1]}}, {"frame_ms", {t_a, t_b}}, {"fixed_ms", fixed},
                 {"per_spp_ms", per_spp}};
  return int(std::clamp(std::round((budget_ms - fixed) / per_spp), 1.0, double(kMaxCalibratedSpp)));
}

// What identifies a run in its record, whatever it renders.
nlohmann::json run_identity(const RunSpec& run, const Scene& scene) {
  return {{"id", run.id},
          {"index", run.index},
          {"group", run.group},
          {"label", run.label},
          {"scene", run.scene},
          {"scene_source", scene.source},
          {"method", run.options["method"]},
          {"variant", run.variant},
          {"axes", run.axes},
          {"seed", run.seed},
          {"images",
           {{"exr", "runs/" + run.id + "/image.exr"}, {"png", "runs/" + run.id + "/image.png"},
            {"error_png", "runs/" + run.id + "/error.png"}}},
          {"spec_hash", run.spec_hash}};
}

RenderOptions run_options(const RunSpec& run) {
  RenderOptions options;
  params_from_json(options, run.options, "run " + run.id);
  return options;
}

// What posing changes in a scene, put back when a sequence run ends, so the runs and references
// after it see the scene as loaded.
class PoseRestorer {
 public:
  explicit PoseRestorer(Scene& scene)
      : scene_(scene), positions_(scene.positions), normals_(scene.normals), cameras_(scene.cameras),
        lights_(scene.lights), bounds_(scene.bounds) {}
  ~PoseRestorer() {
    scene_.positions = std::move(positions_);
    scene_.normals = std::move(normals_);
    scene_.cameras = std::move(cameras_);
    scene_.lights = std::move(lights_);
    scene_.bounds = bounds_;
  }

 private:
  Scene& scene_;
  std::vector<vec3> positions_, normals_;
  std::vector<Camera> cameras_;
  std::vector<PunctualLight> lights_;
  Bounds3 bounds_;
};

// The median over frames of every numeric metric; non-numeric ones from the last frame.
nlohmann::json median_metrics(const std::vector<nlohmann::json>& frames) {
  nlohmann::json out = frames.back();
  for (const auto& [key, value] : frames.back().items()) {
    if (!value.is_number()) continue;
    std::vector<double> v;
    for (const nlohmann::json& f : frames)
      if (f[key].is_number()) v.push_back(f[key].get<double>());
    out[key] = v.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(v));
  }
  return out;
}

const Image& layer_or(const FrameOutput& frame, const char* name, const Image& fallback) {
  for (const Layer& l : frame.extra_layers)
    if (l.name == name) return l.image;
  return fallback;
}

// Median frame time (every stage of a frame, post-processing included) of a short sequence of the
// run at `spp`, without warm-up or references: a probe for equal-time calibration.
double sequence_probe_ms(Scene& scene, const RunSpec& run, int spp) {
  RenderOptions options = run_options(run);
  options.spp = spp;
  options.frames = 3;
  PoseRestorer restore(scene);
  std::vector<KeyFramePath> paths = parse_key_frame_paths(run.paths, scene, "paths");
  std::vector<double> times;
  render_sequence(scene, paths, options, run.method_params, true, [&](SequenceFrame& f) {
    // The first frame pays for the device's and the history's first touch.
    if (f.index > options.frame_start) times.push_back(frame_ms(f.result));
  });
  return median(times);
}

// Equal time for a sequence: the spp whose frame time meets the budget, from the linear model of
// calibrate_spp fitted to two probe sequences (1 and 4 spp). Post-processing costs the same at
// any spp, so it lands in the model's fixed time.
int calibrate_sequence_spp(Scene& scene, const RunSpec& run, double budget_ms, nlohmann::json& calibration) {
  double t_a = sequence_probe_ms(scene, run, kProbeSpp[0]), t_b = sequence_probe_ms(scene, run, kProbeSpp[1]);
  int spp = spp_for_budget(t_a, t_b, budget_ms, calibration);
  calibration["probe_frames"] = 3;
  return spp;
}

// The layer of `frame` an experiment's metrics_layer names.
const Image& measured_layer(const FrameOutput& frame, const std::string& name) {
  return name == "direct" ? frame.direct : name == "indirect" ? frame.indirect : frame.color;
}

// A sequence run: warm-up frames, then measured frames, each against its own reference. Per-frame
// metrics of the output and of the raw frame (before reuse and denoising), their medians, and the
// flicker of both (core/metrics/metrics.h): the record's "metrics" are the medians, so tables and
// reports read sequences as they read single frames. After every frame but the last the run's
// progress is saved (core/eval/sequence_checkpoint.h), and a run that finds its own checkpoint
// continues from it.
void execute_sequence_run(Scene& scene, const RunSpec& run, const FrameReference& frame_reference,
                          const std::string& run_dir, nlohmann::json& record) {
  if (run.metrics_layer != "color")
    throw Error("metrics_layer '" + run.metrics_layer + "' applies to single frames; a sequence is measured on its color");
  RenderOptions options = run_options(run);
  std::string discarded;
  std::optional<SequenceCheckpoint> resumed = load_checkpoint(run_dir, run.spec_hash, discarded);
  if (!discarded.empty()) record["warnings"].push_back(discarded);
  SequenceCheckpoint progress = resumed ? std::move(*resumed) : SequenceCheckpoint{};
  if (resumed) {
    options.spp = progress.spp;
  } else if (run.time_budget_ms > 0.0) {
    options.spp = calibrate_sequence_spp(scene, run, run.time_budget_ms, progress.calibration);
  }
  progress.spp = options.spp;
  if (run.time_budget_ms > 0.0) {
    record["calibration"] = progress.calibration;
    record["time_budget_ms"] = run.time_budget_ms;
  }
  if (resumed) record["resumed_at_frame"] = progress.state.next;
  // A non-resumable method's frame-to-frame state is not in the checkpoint (save_history's is).
  const bool resumable = find_method(options.method).resumable;
  if (!resumable)
    record["checkpoint"] =
        "none: method " + options.method + " keeps frame-to-frame state of its own; an interrupted run starts over";
  const int measured = options.frames;
  options.frames = run.warmup_frames + measured;
  PoseRestorer restore(scene);
  std::vector<KeyFramePath> paths = parse_key_frame_paths(run.paths, scene, "paths");
  fs::path dir(run_dir), preview_dir = dir / "frames";
  SequenceTally& tally = progress.tally;
  RenderResult last;
  render_sequence(
      scene, paths, options, run.method_params, true,
      [&](SequenceFrame& f) {
        const int position = f.index - options.frame_start;
        if (position >= run.warmup_frames) {
          RunReference reference = frame_reference(f.index, f.time, scene);
          const FrameOutput& out = f.result.frame;
          const Image& raw = layer_or(out, "raw", out.color);
          ImageMetrics m = compare_images(out.color, *reference.image), m_raw = compare_images(raw, *reference.image);
          // FLIP of the output only: the raw frames are a diagnosis, and HDR-FLIP costs a
          // tone-mapped LDR-FLIP per exposure.
          nlohmann::json frame_metrics = to_json(m);
          frame_metrics.update(flip_metrics(out.color, *reference.image));
          tally.frames.push_back({{"index", f.index},
                                  {"time", f.time},
                                  {"frame_ms", frame_ms(f.result)},
                                  {"reference", reference.id},
                                  {"metrics", frame_metrics},
                                  {"metrics_raw", to_json(m_raw)},
                                  {"stages", stage_statistics({f.result.timer})},
                                  {"method_counters", out.method_counters}});
          if (!tally.previous.data.empty()) {
            tally.flicker += flicker_mse(tally.previous, out.color, tally.previous_reference, *reference.image);
            tally.flicker_raw += flicker_mse(tally.previous_raw, raw, tally.previous_reference, *reference.image);
            ++tally.pairs;
          }
          tally.previous = out.color;
          tally.previous_raw = raw;
          tally.previous_reference = *reference.image;
          char name[32];
          std::snprintf(name, sizeof name, "frame_%04d.png", position - run.warmup_frames);
          write_image((preview_dir / name).string(), out.color, {}, f.result.options.exposure);
          write_image((preview_dir / ("reference_" + std::string(name + 6))).string(), *reference.image, {},
                      f.result.options.exposure);
          // Every frame has its own reference; the run names the last measured one's.
          tally.reference = reference.id;
          tally.reference_description = reference.description;
        }
        if (resumable && position + 1 < options.frames) save_checkpoint(run_dir, run.spec_hash, progress);
        last = std::move(f.result);
      },
      &progress.state);
  std::vector<nlohmann::json> metrics, metrics_raw;
  std::vector<double> frame_times;
  for (const nlohmann::json& f : tally.frames) {
    metrics.push_back(f["metrics"]);
    metrics_raw.push_back(f["metrics_raw"]);
    frame_times.push_back(f["frame_ms"].get<double>());
  }
  record["reference"] = tally.reference;
  record["reference_description"] = tally.reference_description;
  write_image((dir / "image.exr").string(), last.frame.color, last.frame.layers());
  write_image((dir / "image.png").string(), last.frame.color, {}, last.options.exposure);
  write_image((dir / "error.png").string(), error_heatmap(last.frame.color, tally.previous_reference));
  nlohmann::json videos = nlohmann::json::object();
  for (const char* which : {"frame", "reference"}) {
    std::string video = std::string(which == std::string("frame") ? "video" : "reference") + ".mp4";
    std::string reason = encode_video((preview_dir / (std::string(which) + "_%04d.png")).string(), 0, options.fps,
                                      (dir / video).string());
    videos[which] = reason.empty() ? nlohmann::json("runs/" + run.id + "/" + video) : nlohmann::json(nullptr);
    if (!reason.empty()) record["warnings"].push_back("no preview: " + reason);
  }
  std::error_code ec;
  fs::remove_all(preview_dir, ec);
  nlohmann::json params = params_to_json(last.options);
  params.update(last.method_params);
  params["frames"] = measured;
  record["params"] = params;
  record["spp"] = last.options.spp;
  record["time_ms"] = median_min_max(frame_times);
  record["counters"] = last.frame.counters.to_json(frame_ms(last));
  record["counters"]["method"] = last.frame.method_counters;
  record["device"] = last.device;
  record["metrics"] = median_metrics(metrics);
  record["metrics_raw"] = median_metrics(metrics_raw);
  const int pairs = tally.pairs;
  record["flicker"] = pairs ? nlohmann::json(std::sqrt(tally.flicker / pairs)) : nlohmann::json(nullptr);
  record["flicker_raw"] = pairs ? nlohmann::json(std::sqrt(tally.flicker_raw / pairs)) : nlohmann::json(nullptr);
  record["warmup_frames"] = run.warmup_frames;
  record["frames"] = tally.frames;
  record["videos"] = videos;
  nlohmann::json stages = nlohmann::json::object();
  for (const nlohmann::json& f : tally.frames)
    for (const auto& [stage, t] : f["stages"].items()) stages[stage].push_back(t["median"]);
  for (auto& [stage, values] : stages.items()) stages[stage] = median_min_max(values.get<std::vector<double>>());
  record["stages"] = stages;
}

}  // namespace

bool is_sequence_run(const RunSpec& run) {
  return renders_sequence(run_options(run)) || run.warmup_frames > 0 || !run.paths.is_null();
}

int calibrate_spp(const Scene& scene, const RunSpec& run, double budget_ms, nlohmann::json* probes) {
  // The faster of two renders per probe: timing noise only ever adds time.
  auto probe = [&](int spp) { return std::min(frame_ms(render_run(scene, run, spp)), frame_ms(render_run(scene, run, spp))); };
  double t_a = probe(kProbeSpp[0]);
  double t_b = probe(kProbeSpp[1]);
  nlohmann::json calibration;
  int spp = spp_for_budget(t_a, t_b, budget_ms, calibration);
  if (probes) *probes = calibration;
  return spp;
}

nlohmann::json execute_run(Scene& scene, const RunSpec& run, const RunReference& reference,
                           const FrameReference& frame_reference, const std::string& run_dir) {
  if (is_sequence_run(run)) {
    if (run.repeat > 1) throw Error("run " + run.id + ": repeat times single frames; a sequence's times are medians over its frames");
    nlohmann::json record = run_identity(run, scene);
    record.update({{"reference", nullptr},
                   {"reference_description", nullptr},
                   {"time_budget_ms", nullptr},
                   {"calibration", nullptr},
                   {"repeat", 1},
                   {"scene_summary", scene_summary(scene, run_options(run).diffuse_only)}});
    execute_sequence_run(scene, run, frame_reference, run_dir, record);
    write_json_atomic((fs::path(run_dir) / "run.json").string(), record);
    remove_checkpoint(run_dir);
    return record;
  }
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
  const Image& measured = measured_layer(last.frame, run.metrics_layer);
  write_image((dir / "error.png").string(), error_heatmap(measured, *reference.image));
  ImageMetrics metrics = compare_images(measured, *reference.image);

  nlohmann::json params = params_to_json(last.options);
  params.update(last.method_params);
  nlohmann::json record = run_identity(run, scene);
  record.update({
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
  });
  record["metrics"].update(flip_metrics(measured, *reference.image));
  if (reference.mask) {
    const MaskedErrors e = masked_errors(measured, *reference.image, *reference.mask);
    record["metrics"]["masked"] = {{"pixels", e.pixels}, {"rmse", e.rmse}, {"rel_mse", e.rel_mse}, {"mae", e.mae}};
  }
  record["counters"]["method"] = last.frame.method_counters;
  if (run.metrics_layer != "color") record["metrics_layer"] = run.metrics_layer;
  write_json_atomic((dir / "run.json").string(), record);
  return record;
}

}  // namespace sst
