#include "core/eval/sequence_checkpoint.h"

#include <cstdio>
#include <filesystem>

#include "core/util/error.h"
#include "core/util/json_io.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

fs::path checkpoint_path(const std::string& run_dir) { return fs::path(run_dir) / "checkpoint"; }

std::string numbered(const char* stem, int next, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s-%04d.%s", stem, next, extension);
  return name;
}

}  // namespace

bool has_checkpoint(const std::string& run_dir) { return fs::exists(checkpoint_path(run_dir) / "progress.json"); }

void remove_checkpoint(const std::string& run_dir) {
  std::error_code ec;
  fs::remove_all(checkpoint_path(run_dir), ec);
}

void save_checkpoint(const std::string& run_dir, const std::string& spec_hash, const SequenceCheckpoint& c) {
  const fs::path dir = checkpoint_path(run_dir);
  const std::string state_file = numbered("state", c.state.next, "bin");
  const std::string images_file = numbered("previous", c.state.next, "exr");
  write_sequence_state((dir / state_file).string(), c.state);
  const SequenceTally& t = c.tally;
  const bool measured = !t.previous.data.empty();
  if (measured)
    write_image((dir / images_file).string(), t.previous, {{"raw", t.previous_raw}, {"reference", t.previous_reference}});
  write_json_atomic((dir / "progress.json").string(),
                    {{"spec_hash", spec_hash},
                     {"next", c.state.next},
                     {"spp", c.spp},
                     {"calibration", c.calibration},
                     {"state", state_file},
                     {"previous", measured ? nlohmann::json(images_file) : nlohmann::json(nullptr)},
                     {"frames", t.frames},
                     {"flicker", t.flicker},
                     {"flicker_raw", t.flicker_raw},
                     {"pairs", t.pairs},
                     {"reference", t.reference},
                     {"reference_description", t.reference_description}});
  // The files of earlier frames are no longer named by progress.json.
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != "progress.json" && name != state_file && name != images_file) fs::remove(e.path());
  }
}

std::optional<SequenceCheckpoint> load_checkpoint(const std::string& run_dir, const std::string& spec_hash,
                                                  std::string& discarded) {
  discarded.clear();
  if (!has_checkpoint(run_dir)) return std::nullopt;
  const fs::path dir = checkpoint_path(run_dir);
  try {
    const nlohmann::json p = read_json_file((dir / "progress.json").string());
    if (p.at("spec_hash").get<std::string>() != spec_hash) throw Error("it was saved by a run of another spec");
    SequenceCheckpoint c;
    c.state = read_sequence_state((dir / p.at("state").get<std::string>()).string());
    if (c.state.next != p.at("next").get<int>()) throw Error("its state is of another frame");
    c.spp = p.at("spp").get<int>();
    c.calibration = p.at("calibration");
    SequenceTally& t = c.tally;
    t.frames = p.at("frames").get<std::vector<nlohmann::json>>();
    t.flicker = p.at("flicker").get<double>();
    t.flicker_raw = p.at("flicker_raw").get<double>();
    t.pairs = p.at("pairs").get<int>();
    t.reference = p.at("reference");
    t.reference_description = p.at("reference_description");
    if (!p.at("previous").is_null()) {
      const std::string images = (dir / p.at("previous").get<std::string>()).string();
      t.previous = read_image(images);
      t.previous_raw = read_layer(images, "raw");
      t.previous_reference = read_layer(images, "reference");
    }
    return c;
  } catch (const std::exception& e) {
    discarded = std::string("checkpoint discarded: ") + e.what();
    remove_checkpoint(run_dir);
    return std::nullopt;
  }
}

}  // namespace sst
