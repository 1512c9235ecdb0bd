// sst-eval sweep/merge/table/check as a user runs them: SIGKILL at arbitrary moments then
// --resume, sharding with GNU parallel (and Slurm's variables), and one-line errors.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>

#include "core/util/json_io.h"
#include "tests/core/eval/eval_test_util.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
extern char** environ;

namespace sst {
namespace {

using nlohmann::json;

const json kConfig = {{"width", 32},
                      {"height", 32},
                      {"spp", 4},
                      {"vpls", 1000},
                      {"axes", {{"method", {"slc", "sst", "rtslc", "hybrid", "pt"}}}},
                      {"seeds", 2},
                      {"reference", {{"spp", 64}}}};

fs::path write_config(const fs::path& dir, const json& config = kConfig) {
  fs::path path = dir / "cfg.json";
  std::ofstream(path) << config.dump(2);
  return path;
}

std::string eval_command(const std::string& arguments) { return std::string(SST_EVAL_EXE) + " " + arguments; }

test::CommandResult eval(const std::string& arguments) { return test::run_command(eval_command(arguments)); }

// Starts the command and SIGKILLs it after `delay` (if it is still running).
void run_and_kill(const std::string& command, std::chrono::milliseconds delay) {
  std::string line = "exec " + command + " >/dev/null 2>&1";
  const char* argv[] = {"/bin/sh", "-c", line.c_str(), nullptr};
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ), 0);
  std::this_thread::sleep_for(delay);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
}

TEST(SstEvalSweep, KilledAtAnyMomentAndResumedGivesTheSameResults) {
  fs::path dir = test::temp_dir();
  fs::path config = write_config(dir);
  std::string common = config.string() + " -q --cache-dir " + (dir / "cache").string();
  test::CommandResult whole = eval("sweep " + common + " -o " + (dir / "whole").string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  json expected = test::without_timings(read_json_file((dir / "whole/results.json").string()));
  // Kill points spread over the sweep: while the reference renders, between and inside runs.
  int i = 0;
  for (int ms : {20, 120, 250, 400, 550}) {
    fs::path out = dir / ("killed" + std::to_string(i++));
    std::string args = config.string() + " -q --cache-dir " + (dir / ("cache-k" + std::to_string(i))).string() +
                       " -o " + out.string();
    run_and_kill(eval_command("sweep " + args), std::chrono::milliseconds(ms));
    test::CommandResult resumed = eval("sweep --resume " + args);
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(test::without_timings(read_json_file((out / "results.json").string())), expected) << "killed after " << ms << " ms";
  }
}

TEST(SstEvalSweep, ShardsRunWithGnuParallelAndMerge) {
  if (test::run_command("parallel --version").exit_code != 0) GTEST_SKIP() << "GNU parallel is not installed";
  fs::path dir = test::temp_dir();
  fs::path config = write_config(dir);
  std::string common = config.string() + " -q --cache-dir " + (dir / "cache").string();
  ASSERT_EQ(eval("sweep " + common + " -o " + (dir / "whole").string()).exit_code, 0);
  test::CommandResult sharded = test::run_command("parallel --will-cite -j 3 " + eval_command("sweep " + common) +
                                                  " --shard {}/3 -o " + (dir / "shard{}").string() + " ::: 0 1 2");
  ASSERT_EQ(sharded.exit_code, 0) << sharded.output;
  test::CommandResult merged = eval("merge " + (dir / "shard0").string() + " " + (dir / "shard1").string() + " " +
                                    (dir / "shard2").string() + " -o " + (dir / "merged").string());
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  EXPECT_EQ(test::without_timings(read_json_file((dir / "merged/results.json").string())),
            test::without_timings(read_json_file((dir / "whole/results.json").string())));
  test::CommandResult incomplete = eval("merge " + (dir / "shard0").string() + " -o " + (dir / "partial").string());
  EXPECT_EQ(incomplete.exit_code, 1);
  EXPECT_NE(incomplete.output.find("error: merge: 6 of 10 runs are missing"), std::string::npos) << incomplete.output;
}

TEST(SstEvalSweep, SlurmArrayVariablesSelectTheShard) {
  fs::path dir = test::temp_dir();
  fs::path config = write_config(dir, {{"width", 16}, {"axes", {{"method", {"pt", "slc", "sst"}}}}, {"reference", {{"spp", 8}}}});
  test::CommandResult r = test::run_command("SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=2 " +
                                            eval_command("sweep -q " + config.string() + " --cache-dir " +
                                                         (dir / "cache").string() + " -o " + (dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json shard = read_json_file((dir / "out/shards/shard-1-of-2.json").string());
  ASSERT_EQ(shard["runs"].size(), 1u);
  EXPECT_EQ(shard["runs"][0]["id"], "0001-slc");
}

TEST(SstEvalSweep, BadInputIsOneLineAndKeepsFinishedRuns) {
  fs::path dir = test::temp_dir();
  std::ofstream(dir / "bad.json") << R"({"widht": 32})";
  test::CommandResult r = eval("sweep " + (dir / "bad.json").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output, "error: " + (dir / "bad.json").string() + ": unknown key 'widht' (did you mean 'width'?)\n");
  fs::path config = write_config(dir, {{"width", 16}, {"method", "pt"}, {"reference", {{"spp", 8}}}});
  std::string args = config.string() + " -q --cache-dir " + (dir / "cache").string() + " -o " + (dir / "out").string();
  ASSERT_EQ(eval("sweep " + args).exit_code, 0);
  test::CommandResult again = eval("sweep " + args);
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_NE(again.output.find("pass --resume"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "out/runs/0000-pt/run.json"));
}

TEST(SstEvalSweep, TablePrintsMarkdownAndCsv) {
  fs::path dir = test::temp_dir();
  fs::path config = write_config(dir, {{"width", 16}, {"axes", {{"method", {"pt", "slc"}}, {"spp", {1, 2}}}}, {"reference", {{"spp", 8}}}});
  ASSERT_EQ(eval("sweep -q " + config.string() + " --cache-dir " + (dir / "cache").string() + " -o " + (dir / "out").string()).exit_code, 0);
  test::CommandResult md = eval("table " + (dir / "out").string() + " --stage sampling");
  ASSERT_EQ(md.exit_code, 0) << md.output;
  EXPECT_EQ(md.output.rfind("| method | spp | frame ms (median [min-max]) | sampling ms | RMSE |", 0), 0u) << md.output;
  EXPECT_NE(md.output.find("| SSIM | LDR-FLIP | HDR-FLIP |"), std::string::npos) << md.output;
  EXPECT_EQ(std::count(md.output.begin(), md.output.end(), '\n'), 2 + 4);
  // Every run records both FLIP means, the groups their statistics, the CSV its columns.
  const json results = read_json_file((dir / "out/results.json").string());
  for (const json& r : results["runs"])
    for (const char* key : {"flip_ldr", "flip_hdr"}) {
      ASSERT_TRUE(r["metrics"][key].is_number()) << key << " " << r["id"];
      EXPECT_GT(r["metrics"][key].get<double>(), 0.0);
      EXPECT_LE(r["metrics"][key].get<double>(), 1.0);
    }
  EXPECT_TRUE(results["groups"][0]["flip_hdr_median"].is_number());
  std::ifstream csv_file(dir / "out/results.csv");
  const std::string csv_text((std::istreambuf_iterator<char>(csv_file)), std::istreambuf_iterator<char>());
  EXPECT_NE(csv_text.find(",reference,flip_ldr,flip_hdr\n"), std::string::npos) << csv_text;
  test::CommandResult csv = eval("table " + (dir / "out/results.json").string() + " --format csv");
  EXPECT_EQ(csv.output.rfind("method,spp,frame ms", 0), 0u) << csv.output;
  EXPECT_EQ(eval("table " + (dir / "out").string() + " --format xml").exit_code, 1);
}

// A reference with "mask": every run's metrics gain the errors on the pixels no visible emitter
// touches (the Cornell box's lamp is in view: fewer pixels than the image, but most), and the
// table their columns.
TEST(SstEvalSweep, AMaskedReferenceMeasuresThePixelsNoEmitterTouches) {
  fs::path dir = test::temp_dir();
  fs::path config = write_config(dir, {{"width", 32}, {"height", 32}, {"method", "pt"}, {"max_bounces", 0}, {"spp", 2},
                                       {"reference", {{"spp", 16}, {"max_bounces", 0}, {"mask", true}}}});
  test::CommandResult run = eval("sweep -q " + config.string() + " --cache-dir " + (dir / "cache").string() + " -o " +
                                 (dir / "out").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  json results = read_json_file((dir / "out/results.json").string());
  ASSERT_EQ(results["runs"].size(), 1u);
  const json& m = results["runs"][0]["metrics"];
  ASSERT_TRUE(m.contains("masked")) << m.dump();
  const size_t pixels = m["masked"]["pixels"].get<size_t>();
  EXPECT_GT(pixels, 32u * 32u / 2);
  EXPECT_LT(pixels, 32u * 32u);
  EXPECT_GT(m["masked"]["rmse"].get<double>(), 0.0);
  test::CommandResult md = eval("table " + (dir / "out").string());
  EXPECT_NE(md.output.find("| RMSE | relMSE | MSE masked | relMSE masked |"), std::string::npos) << md.output;
  std::ifstream report(dir / "out/report.html");
  const std::string html((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("rel MSE masked"), std::string::npos);
}

}  // namespace
}  // namespace sst

namespace sst {
namespace {

// A sequence sweep end to end: warm-up and measured frames, per-frame references, raw and output
// metrics, flicker, videos, and the report's sequence table and per-frame plots.
TEST(SstEvalSweep, SequencesAreMeasuredFrameByFrameWithFlicker) {
  fs::path dir = test::temp_dir();
  const json config = {{"width", 24},
                       {"height", 24},
                       {"spp", 1},
                       {"vpls", 500},
                       {"frames", 3},
                       {"warmup_frames", 2},
                       {"temporal", true},
                       {"paths", json::parse(R"([{"camera": "", "keys": [{"time": 0}, {"time": 1, "yaw_degrees": 15}]}])")},
                       {"axes", {{"method", {"pt", "sst"}}, {"denoise", {"none", "svgf"}}}},
                       {"reference", {{"spp", 16}}}};
  fs::path cfg = write_config(dir, config);
  test::CommandResult r = eval("sweep " + cfg.string() + " -q -o " + (dir / "out").string() + " --cache-dir " +
                               (dir / "cache").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json results = read_json_file((dir / "out" / "results.json").string());
  ASSERT_EQ(results["runs"].size(), 4u);
  std::set<std::string> references;
  for (const json& run : results["runs"]) {
    ASSERT_EQ(run["frames"].size(), 3u) << run["id"];
    EXPECT_EQ(run["warmup_frames"], 2);
    EXPECT_EQ(run["frames"][0]["index"], 2);  // after the warm-up
    for (const json& f : run["frames"]) references.insert(f["reference"].get<std::string>());
    EXPECT_TRUE(run["flicker"].is_number()) << run.dump();
    EXPECT_TRUE(run["flicker_raw"].is_number());
    EXPECT_TRUE(run["metrics_raw"]["rmse"].is_number());
    // FLIP per measured frame of the output, its median the run's.
    EXPECT_TRUE(run["frames"][0]["metrics"]["flip_hdr"].is_number());
    EXPECT_TRUE(run["metrics"]["flip_ldr"].is_number());
    // Each frame's method counters; the run's are the last frame's.
    EXPECT_EQ(run["frames"].back()["method_counters"], run["counters"]["method"]);
    if (run["method"] == "sst") {
      EXPECT_TRUE(run["frames"][0]["method_counters"].contains("nodes_visited_mean"));
    }
    // Temporal reuse makes the output steadier than the raw frames it comes from.
    EXPECT_LT(run["flicker"].get<double>(), run["flicker_raw"].get<double>()) << run["id"];
    EXPECT_TRUE(fs::exists(dir / "out" / "runs" / run["id"].get<std::string>() / "image.exr"));
    if (!run["videos"]["frame"].is_null()) {
      EXPECT_TRUE(fs::exists(dir / "out" / run["videos"]["frame"].get<std::string>()));
    }
  }
  // One reference per measured frame, shared by the runs (the same pose and reference settings).
  EXPECT_EQ(references.size(), 3u);
  std::ifstream report(dir / "out" / "report.html");
  std::string html((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("flicker out"), std::string::npos);
  EXPECT_NE(html.find("<th>HDR-FLIP"), std::string::npos);  // the groups' and the runs' columns
  EXPECT_NE(html.find("RMSE per frame"), std::string::npos);
}

TEST(SstEvalSweep, SequencesAreCalibratedToATimeBudget) {
  fs::path dir = test::temp_dir();
  const json config = {{"width", 24}, {"height", 24}, {"frames", 2}, {"temporal", true}, {"method", "pt"},
                       {"time_budget_ms", 50.0}, {"reference", {{"spp", 8}}}};
  fs::path cfg = write_config(dir, config);
  test::CommandResult r = eval("sweep " + cfg.string() + " -q -o " + (dir / "out").string() + " --cache-dir " +
                               (dir / "cache").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  json run = read_json_file((dir / "out" / "results.json").string())["runs"][0];
  EXPECT_EQ(run["time_budget_ms"], 50.0);
  ASSERT_TRUE(run["calibration"].is_object()) << run.dump();
  EXPECT_GT(run["calibration"]["per_spp_ms"].get<double>(), 0.0);
  // A 24x24 path-traced frame takes well under a millisecond per spp: the budget buys many.
  EXPECT_GT(run["spp"].get<int>(), 4);
}

}  // namespace
}  // namespace sst
