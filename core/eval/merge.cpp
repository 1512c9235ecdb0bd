#include "core/eval/merge.h"

#include <filesystem>
#include <map>

#include "core/eval/experiment_config.h"
#include "core/eval/results.h"
#include "core/eval/sweep.h"
#include "core/util/error.h"
#include "core/util/json_io.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

ExperimentConfig read_sweep_config(const std::string& dir) {
  std::string path = (fs::path(dir) / "config.json").string();
  if (!fs::exists(path)) throw Error(dir + ": not a sweep output folder (no config.json)");
  nlohmann::json j = read_json_file(path);
  ExperimentConfig c = parse_experiment_config(j.at("config"), path);
  c.name = j.value("name", c.name);
  return c;
}

void copy_into(const fs::path& from, const fs::path& to) {
  if (fs::exists(to) || !fs::exists(from)) return;
  fs::create_directories(to.parent_path());
  fs::copy(from, to, fs::copy_options::recursive);
}

}  // namespace

nlohmann::json merge_sweep(const std::vector<std::string>& shard_dirs, const std::string& output_dir) {
  if (shard_dirs.empty()) throw Error("merge: no shard folders given");
  ExperimentConfig config = read_sweep_config(shard_dirs.front());
  for (const std::string& dir : shard_dirs)
    if (read_sweep_config(dir).source != config.source)
      throw Error(dir + ": holds a different config than " + shard_dirs.front() + "; shards of one sweep only");
  std::vector<RunSpec> runs = expand_runs(config);
  fs::create_directories(output_dir);
  std::map<std::string, nlohmann::json> found;
  for (const std::string& dir : shard_dirs) {
    bool same = fs::weakly_canonical(dir) == fs::weakly_canonical(output_dir);
    for (nlohmann::json& record : finished_runs(dir, runs)) {
      std::string id = record["id"];
      if (!same) {
        copy_into(fs::path(dir) / "runs" / id, fs::path(output_dir) / "runs" / id);
        for (const char* ext : {".exr", ".png"}) {
          std::string ref = "references/" + record["reference"].get<std::string>() + ext;
          copy_into(fs::path(dir) / ref, fs::path(output_dir) / ref);
        }
      }
      found.emplace(id, std::move(record));
    }
  }
  std::vector<std::string> missing;
  for (const RunSpec& run : runs)
    if (!found.count(run.id)) missing.push_back(run.id);
  if (!missing.empty())
    throw Error("merge: " + std::to_string(missing.size()) + " of " + std::to_string(runs.size()) +
                " runs are missing (first: " + missing.front() + "); render them with sweep --resume --shard i/n");
  std::vector<nlohmann::json> records;
  for (auto& [id, record] : found) records.push_back(std::move(record));
  write_json_atomic((fs::path(output_dir) / "config.json").string(),
                    {{"name", config.name}, {"config", config.source}, {"runs", runs.size()}});
  nlohmann::json results = assemble_results(config, records, output_dir);
  write_results(results, output_dir);
  return results;
}

}  // namespace sst
