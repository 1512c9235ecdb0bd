// The progress of a sequence run, saved under <run_dir>/checkpoint after every frame but the last,
// so that `sst-eval sweep --resume` continues an interrupted run at its next frame instead of
// redoing it, with the images and numbers the uninterrupted run would have had: the sequence's
// state (core/pipeline/sequence_state.h), the measurements of the frames so far and the images the
// next frame's flicker is measured against. progress.json is written last and names the files of
// its frame, so a checkpoint is whole or absent.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image.h"
#include "core/pipeline/sequence_state.h"

namespace sst {

// What the measured frames so far add up to.
struct SequenceTally {
  std::vector<nlohmann::json> frames;         // per measured frame: index, time, frame_ms, metrics, ...
  double flicker = 0.0, flicker_raw = 0.0;    // sums of flicker_mse over consecutive measured frames
  int pairs = 0;                              // ... and how many pairs they sum
  Image previous, previous_raw, previous_reference;  // the last measured frame: output, raw, reference
  nlohmann::json reference = nullptr;         // its reference's id and description
  nlohmann::json reference_description = nullptr;
};

struct SequenceCheckpoint {
  SequenceState state;
  SequenceTally tally;
  int spp = 0;                                // the spp rendered (calibrated ones are not probed again)
  nlohmann::json calibration = nullptr;
};

// Whether <run_dir> holds a checkpoint (of any run).
bool has_checkpoint(const std::string& run_dir);
// The checkpoint in <run_dir> if it was written for the run whose spec_hash is `spec_hash`. One of
// another spec, or unreadable, is deleted, and `discarded` says why.
std::optional<SequenceCheckpoint> load_checkpoint(const std::string& run_dir, const std::string& spec_hash,
                                                  std::string& discarded);
void save_checkpoint(const std::string& run_dir, const std::string& spec_hash, const SequenceCheckpoint& checkpoint);
void remove_checkpoint(const std::string& run_dir);

}  // namespace sst
