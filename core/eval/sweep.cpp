#include "core/eval/sweep.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

#include "core/eval/reference.h"
#include "core/util/hash.h"
#include "core/eval/results.h"
#include "core/eval/run_executor.h"
#include "core/eval/sequence_checkpoint.h"
#include "core/scene/animation.h"
#include "core/scene/default_scene.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/scene_search.h"
#include "core/util/error.h"
#include "core/util/json_io.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

using Clock = std::chrono::steady_clock;

std::string run_json_path(const std::string& dir, const RunSpec& run) {
  return (fs::path(dir) / "runs" / run.id / "run.json").string();
}

// The scene of the runs being rendered: loaded when the sweep reaches it, with its content hash.
struct LoadedScene {
  std::string name;
  std::unique_ptr<Scene> scene;
  std::string content_hash;
};

void load_scene(LoadedScene& loaded, const std::string& name, const SweepOptions& options) {
  if (loaded.scene && loaded.name == name) return;
  std::string path = name.empty() ? "" : resolve_scene(name, options.scene_dirs);
  loaded.scene = std::make_unique<Scene>(path.empty() ? load_default_scene() : load_gltf(path));
  loaded.content_hash = scene_content_hash(path);
  loaded.name = name;
}

// The reference of a run: from the cache (rendered there once), copied beside the results as a
// float EXR (for bias and variance) and a PNG (for the report).
class ReferenceStore {
 public:
  ReferenceStore(const SweepOptions& options, const nlohmann::json& config)
      : cache_(options.cache_dir), dir_(options.output_dir), config_(config), quiet_(options.quiet) {}

  RunReference get(const RunSpec& run, const LoadedScene& scene) {
    ReferenceSpec spec = reference_for(run, config_, scene.content_hash);
    auto it = images_.find(spec.id);
    if (it == images_.end()) {
      nlohmann::json record;
      Image image = cache_.get(spec, *scene.scene, quiet_, &record);
      fs::path base = fs::path(dir_) / "references" / spec.id;
      if (!fs::exists(base.string() + ".exr")) write_image(base.string() + ".exr", image);
      if (!fs::exists(base.string() + ".png")) write_image(base.string() + ".png", image);
      double render_ms = 0.0;
      for (const auto& [stage, t] : record["timings_ms"].items())
        if (stage != "load" && stage != "write") render_ms += t["median"].get<double>();
      descriptions_[spec.id] = {{"id", spec.id}, {"kind", spec.kind}, {"scene", spec.scene}, {"options", spec.options},
                                {"method_params", spec.method_params}, {"render_ms", render_ms}};
      it = images_.emplace(spec.id, std::move(image)).first;
    }
    RunReference reference{spec.id, descriptions_[spec.id], &it->second};
    if (config_.value("mask", false)) {
      const ReferenceSpec mask = emitter_mask_for(spec);
      auto m = images_.find(mask.id);
      if (m == images_.end()) m = images_.emplace(mask.id, cache_.get(mask, emitters_only(*scene.scene), quiet_)).first;
      reference.mask = &m->second;
    }
    return reference;
  }

  // The reference of frame `index` of a sequence run, on the scene as posed then: cached on disk
  // under the run's reference and the frame's time and paths, kept in memory only while it is the
  // latest (a sequence's references are many and used once per run).
  RunReference get_frame(const RunSpec& run, const LoadedScene& scene, int index, double time, const Scene& posed) {
    ReferenceSpec spec = reference_for(run, config_, scene.content_hash);
    if (spec.kind != "path") throw Error("run " + run.id + ": a sequence needs a 'path' reference (each frame has its own)");
    // Nothing moves: every frame has the run's one reference.
    if (run.paths.is_null() && !posed.animation) return get(run, scene);
    nlohmann::json frame = {{"reference", spec.id}, {"index", index}, {"time", time}, {"paths", run.paths}};
    spec.id = Hash64().add(frame.dump()).hex();
    nlohmann::json record;
    frame_image_ = cache_.get(spec, posed, quiet_, &record);
    fs::path base = fs::path(dir_) / "references" / spec.id;
    if (!fs::exists(base.string() + ".exr")) write_image(base.string() + ".exr", frame_image_);
    if (!fs::exists(base.string() + ".png")) write_image(base.string() + ".png", frame_image_);
    nlohmann::json description = {{"id", spec.id}, {"kind", spec.kind}, {"scene", spec.scene}, {"options", spec.options},
                                  {"method_params", spec.method_params}, {"frame", index}, {"time", time}};
    return {spec.id, description, &frame_image_};
  }

 private:
  ReferenceCache cache_;
  std::string dir_;
  nlohmann::json config_;
  bool quiet_;
  std::map<std::string, Image> images_;
  std::map<std::string, nlohmann::json> descriptions_;
  Image frame_image_;
};

void check_output_dir(const SweepOptions& options, const std::vector<RunSpec>& runs) {
  if (options.resume) return;
  for (const RunSpec& run : runs) {
    if (fs::exists(run_json_path(options.output_dir, run)))
      throw Error(options.output_dir + ": holds finished runs of an earlier sweep (e.g. " + run.id +
                  "); pass --resume to continue it, or choose another -o");
    if (has_checkpoint((fs::path(options.output_dir) / "runs" / run.id).string()))
      throw Error(options.output_dir + ": holds the unfinished sequence run " + run.id +
                  " of an earlier sweep; pass --resume to continue it, or choose another -o");
  }
}

std::string duration(double seconds) {
  char text[32];
  if (seconds < 60) std::snprintf(text, sizeof text, "%.0fs", seconds);
  else if (seconds < 3600) std::snprintf(text, sizeof text, "%.0fm%02.0fs", std::floor(seconds / 60), std::fmod(seconds, 60));
  else std::snprintf(text, sizeof text, "%.0fh%02.0fm", std::floor(seconds / 3600), std::fmod(seconds, 3600) / 60);
  return text;
}

void report_progress(size_t done, size_t total, size_t rendered, size_t rendered_total, Clock::time_point start,
                     const nlohmann::json& record) {
  double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  double left = rendered > 0 ? elapsed / double(rendered) * double(rendered_total - rendered) : 0.0;
  const nlohmann::json& m = record["metrics"];
  auto value = [&](const char* key) { return m.contains(key) && m[key].is_number() ? m[key].get<double>() : NAN; };
  std::fprintf(stderr, "[%zu/%zu] %s: %d spp, frame %.1f ms, rmse %.4g, ssim %.4f, flip %.4f | %s elapsed, ~%s left\n",
               done, total, record["id"].get<std::string>().c_str(), record["spp"].get<int>(),
               record["time_ms"]["median"].get<double>(), value("rmse"), value("ssim"), value("flip_ldr"),
               duration(elapsed).c_str(), duration(left).c_str());
}

}  // namespace

void parse_shard(const std::string& text, int& index, int& count) {
  int i = -1, n = -1;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &tail) != 2 || n < 1 || i < 0 || i >= n)
    throw Error("--shard '" + text + "': expected i/n with 0 <= i < n");
  index = i;
  count = n;
}

bool shard_from_slurm(int& index, int& count) {
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* n = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (!id || !n) return false;
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  parse_shard(std::to_string(std::atoi(id) - (min ? std::atoi(min) : 0)) + "/" + n, index, count);
  return true;
}

std::vector<nlohmann::json> finished_runs(const std::string& dir, const std::vector<RunSpec>& runs) {
  std::vector<nlohmann::json> records;
  for (const RunSpec& run : runs) {
    std::string path = run_json_path(dir, run);
    if (!fs::exists(path)) continue;
    nlohmann::json record = read_json_file(path);
    if (record.value("spec_hash", std::string()) == run.spec_hash) records.push_back(std::move(record));
  }
  return records;
}

nlohmann::json run_sweep(const ExperimentConfig& config, const SweepOptions& options) {
  std::vector<RunSpec> all = expand_runs(config);
  std::vector<RunSpec> mine;
  for (const RunSpec& run : all)
    if (run.index % options.shard_count == options.shard_index) mine.push_back(run);
  check_output_dir(options, mine);
  write_json_atomic((fs::path(options.output_dir) / "config.json").string(),
                    {{"name", config.name}, {"config", config.source}, {"runs", all.size()}});

  std::map<std::string, nlohmann::json> done;
  for (nlohmann::json& r : finished_runs(options.output_dir, mine)) {
    std::string id = r["id"];
    done[id] = std::move(r);
  }
  size_t to_render = mine.size() - done.size(), rendered = 0, finished = done.size();
  if (!options.quiet && !done.empty())
    std::fprintf(stderr, "resuming: %zu of %zu runs already finished\n", done.size(), mine.size());

  LoadedScene scene;
  ReferenceStore references(options, config.reference);
  Clock::time_point start = Clock::now();
  std::vector<nlohmann::json> records;
  for (const RunSpec& run : mine) {
    if (auto it = done.find(run.id); it != done.end()) {
      records.push_back(it->second);
      continue;
    }
    load_scene(scene, run.scene, options);
    const bool sequence = is_sequence_run(run);
    RunReference reference = sequence ? RunReference{} : references.get(run, scene);
    FrameReference frame_reference = [&](int index, double time, const Scene& posed) {
      return references.get_frame(run, scene, index, time, posed);
    };
    records.push_back(execute_run(*scene.scene, run, reference, frame_reference,
                                  (fs::path(options.output_dir) / "runs" / run.id).string()));
    ++rendered;
    if (!options.quiet) report_progress(++finished, mine.size(), rendered, to_render, start, records.back());
  }

  if (options.shard_count > 1) {
    nlohmann::json shard = {{"name", config.name},
                            {"shard", std::to_string(options.shard_index) + "/" + std::to_string(options.shard_count)},
                            {"runs", records}};
    write_json_atomic((fs::path(options.output_dir) / "shards" /
                       ("shard-" + std::to_string(options.shard_index) + "-of-" + std::to_string(options.shard_count) + ".json"))
                          .string(),
                      shard);
    return shard;
  }
  nlohmann::json results = assemble_results(config, records, options.output_dir);
  write_results(results, options.output_dir);
  return results;
}

}  // namespace sst
