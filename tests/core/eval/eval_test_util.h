// What the eval tests share: a results.json without the fields that depend on timing, for
// comparing two sweeps that must agree in everything else; a small sequence run interrupted and
// resumed from its checkpoint.
#pragma once
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "core/eval/experiment_config.h"
#include "core/eval/run_executor.h"
#include "core/eval/sequence_checkpoint.h"
#include "core/image/image.h"
#include "core/scene/default_scene.h"
#include "core/util/error.h"
#include "tests/test_util.h"

namespace sst::test {

inline nlohmann::json without_timings(nlohmann::json r) {
  r.erase("machine");
  for (nlohmann::json& run : r["runs"]) {
    for (const char* k : {"time_ms", "stages", "counters", "efficiency", "ssim_gain_pct_per_ms", "gain_base"}) run.erase(k);
    run["reference_description"].erase("render_ms");
  }
  for (nlohmann::json& g : r["groups"]) g.erase("time_ms_median"), g.erase("pareto");
  for (auto& [id, ref] : r["references"].items()) ref.erase("render_ms");
  return r;
}

// The run of config `fields` at 24x24: four measured frames after two warm-up frames, the camera
// turning.
inline RunSpec tiny_sequence_run(const nlohmann::json& fields) {
  nlohmann::json j = {{"width", 24}, {"height", 24}, {"frames", 4}, {"warmup_frames", 2}, {"reference", {{"spp", 16}}},
            {"paths", nlohmann::json::parse(R"([{"camera": "", "keys": [{"time": 0}, {"time": 1, "yaw_degrees": 20}]}])")}};
  j.update(fields);
  ExperimentConfig c = parse_experiment_config(j, "tiny");
  c.name = "tiny";
  return expand_runs(c).at(0);
}

// Frame references that count their calls and throw at frame `interrupt_at`, as an interruption
// after that frame rendered.
struct InterruptingReferences {
  Image image{24, 24};
  int calls = 0, interrupt_at = -1;
  InterruptingReferences() {
    for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = 0.02f * float(i % 37);
  }
  FrameReference function() {
    return [this](int index, double, const Scene&) {
      ++calls;
      if (index == interrupt_at) throw Error("interrupted");
      return RunReference{"fixed", nlohmann::json::object(), &image};
    };
  }
};

// `run` whole, then interrupted after its third measured frame and resumed (in `cut_dir`): the
// resumed run renders only the frames that remained and ends with the whole run's numbers and image.
inline nlohmann::json expect_resumes(const RunSpec& run, const std::string& whole_dir, const std::string& cut_dir) {
  Scene scene = load_default_scene();
  InterruptingReferences references;
  nlohmann::json whole = execute_run(scene, run, {}, references.function(), whole_dir);
  EXPECT_FALSE(has_checkpoint(whole_dir));
  EXPECT_FALSE(whole.contains("checkpoint")) << whole["checkpoint"];  // resumable
  references.interrupt_at = 4;  // the third of the measured frames 2-5
  EXPECT_THROW(execute_run(scene, run, {}, references.function(), cut_dir), Error);
  EXPECT_TRUE(has_checkpoint(cut_dir));
  references.interrupt_at = -1;
  references.calls = 0;
  nlohmann::json resumed = execute_run(scene, run, {}, references.function(), cut_dir);
  EXPECT_EQ(references.calls, 2);  // frames 4 and 5 only
  EXPECT_EQ(resumed["resumed_at_frame"], 4);
  EXPECT_FALSE(has_checkpoint(cut_dir));
  for (const char* key : {"metrics", "metrics_raw", "flicker", "flicker_raw", "spp"}) EXPECT_EQ(resumed[key], whole[key]) << key;
  EXPECT_EQ(resumed["frames"].size(), 4u);
  for (size_t i = 0; i < 4 && i < resumed["frames"].size(); ++i)
    EXPECT_EQ(resumed["frames"][i]["metrics"], whole["frames"][i]["metrics"]) << i;
  EXPECT_EQ(read_image(cut_dir + "/image.exr").data, read_image(whole_dir + "/image.exr").data);
  return whole;
}

}  // namespace sst::test
