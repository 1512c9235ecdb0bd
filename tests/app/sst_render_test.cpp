// sst-render end to end: the default scene, the JSON record, and every kind of bad input giving
// one line and a non-zero exit.
#include <gtest/gtest.h>

#include "core/pipeline/backend.h"

#include <filesystem>
#include <fstream>

#include "core/image/image.h"
#include "core/pipeline/backend.h"
#include "core/util/json_io.h"
#include "tests/test_util.h"

namespace sst {
namespace {

std::string render_cmd(const std::string& args) { return std::string(SST_RENDER_EXE) + " " + args; }

// The output holds exactly one line, starting with "error: " and containing `needle`.
void expect_one_line_error(const test::CommandResult& r, const std::string& needle) {
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.rfind("error: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << r.output;
}

TEST(SstRender, DefaultSceneWritesImageAovsAndRecord) {
  auto dir = test::temp_dir();
  auto exr = (dir / "cornell.exr").string();
  auto png = (dir / "cornell.png").string();
  auto r = test::run_command(render_cmd("-o " + exr + " -o " + png + " --width 48 --spp 2 -q"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");  // --quiet
  Image img = read_image(exr);
  EXPECT_EQ(img.width, 48);
  EXPECT_EQ(img.height, 48);  // the camera's aspect ratio is 1
  for (const char* layer : {"direct", "indirect", "albedo", "normal", "depth"})
    EXPECT_NO_THROW(read_layer(exr, layer)) << layer;
  EXPECT_TRUE(std::filesystem::exists(png));

  nlohmann::json rec = read_json_file((dir / "cornell.json").string());
  EXPECT_EQ(rec["schema_version"], 1);
  EXPECT_EQ(rec["tool"], "sst-render");
  EXPECT_FALSE(rec["revision"].get<std::string>().empty());
  EXPECT_TRUE(rec["machine"].contains("cpu"));
  EXPECT_EQ(rec["scene"]["source"], "builtin:cornell-box");
  EXPECT_EQ(rec["options"]["width"], 48);
  EXPECT_EQ(rec["options"]["spp"], 2);
  EXPECT_EQ(rec["method_params"]["max_bounces"], 8);
  for (const char* stage : {"load", "accel_build", "render", "write"})
    EXPECT_TRUE(rec["timings_ms"].contains(stage)) << stage;
  EXPECT_EQ(rec["counters"]["primary_rays"], 48 * 48 * 2);
  EXPECT_EQ(rec["counters"]["nonfinite_samples"], 0);
  EXPECT_GT(rec["counters"]["mrays_per_s"].get<double>(), 0.0);
}

// --emitters-only leaves the lamp alone in the Cornell box: its pixels hold its radiance, every
// pixel that does not see it is black, at any number of bounces.
TEST(SstRender, EmittersOnlyShowsTheLampAlone) {
  auto dir = test::temp_dir();
  auto exr = (dir / "mask.exr").string();
  auto r = test::run_command(render_cmd("-o " + exr + " --width 32 --spp 4 -q --emitters-only"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  Image img = read_image(exr);
  int lit = 0;
  float brightest = 0.0f;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const vec3 c = img.rgb(x, y);
      if (c != vec3(0.0f)) ++lit;
      brightest = std::max(brightest, c.x);
    }
  EXPECT_GT(lit, 0);
  EXPECT_LT(lit, 32 * 32 / 10);    // the lamp is a small part of the view
  EXPECT_GT(brightest, 1.0f);       // the lamp's radiance, not a reflection of it
  EXPECT_EQ(img.rgb(16, 31), vec3(0.0f));  // the floor in front of the camera
}

TEST(SstRender, RepeatReportsMedianMinMax) {
  auto dir = test::temp_dir();
  auto r = test::run_command(render_cmd("-o " + (dir / "a.exr").string() + " --width 16 --spp 1 --repeat 3 -q"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  nlohmann::json rec = read_json_file((dir / "a.json").string());
  EXPECT_EQ(rec["repeat"], 3);
  auto t = rec["timings_ms"]["render"];
  EXPECT_LE(t["min"].get<double>(), t["median"].get<double>());
  EXPECT_LE(t["median"].get<double>(), t["max"].get<double>());
}

TEST(SstRender, BadInputIsOneLineAndNonZeroExit) {
  auto dir = test::temp_dir();
  std::string out = " -o " + (dir / "x.exr").string() + " --width 8 --spp 1 -q";
  expect_one_line_error(test::run_command(render_cmd("/no/such/scene.gltf" + out)), "/no/such/scene.gltf");
  expect_one_line_error(test::run_command(render_cmd("--method ptt" + out)), "did you mean 'pt'");
  expect_one_line_error(test::run_command(render_cmd("--spp 0 -o " + (dir / "y.exr").string())), "spp");
  expect_one_line_error(test::run_command(render_cmd("--max-bounces many" + out)), "--max-bounces");
  expect_one_line_error(test::run_command(render_cmd("--max-bounces -2" + out)), "max_bounces");
  expect_one_line_error(test::run_command(render_cmd("--camera nope" + out)), "nope");
  expect_one_line_error(test::run_command(render_cmd("-o " + (dir / "x.bmp").string() + " --width 8 --spp 1 -q")), ".bmp");
  auto unknown_flag = test::run_command(render_cmd("--no-such-flag" + out));
  EXPECT_NE(unknown_flag.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));  // nothing half-written
}

TEST(SstRender, ListMethodsShowsParameterTables) {
  auto r = test::run_command(render_cmd("--list-methods"));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.output.find("pt:"), std::string::npos);
  EXPECT_NE(r.output.find("--max-bounces"), std::string::npos);
  // --markdown is a form of --list-methods, not a render option.
  EXPECT_NE(test::run_command(render_cmd("--markdown")).exit_code, 0);
}

TEST(SstRender, ListDevicesPrintsDevicesOrReason) {
  auto r = test::run_command(render_cmd("--list-devices"));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(r.output.empty());
  bool listed = r.output.rfind("0: ", 0) == 0 && r.output.find("max storage buffer") != std::string::npos;
  bool reason = r.output.rfind("no Vulkan device: ", 0) == 0;
  EXPECT_TRUE(listed || reason) << r.output;
}

TEST(SstRender, BackendChoices) {
  auto dir = test::temp_dir();
  std::string out = " -o " + (dir / "b.exr").string() + " --width 8 --spp 1";
  // auto says what it chose and why; the record names the backend that ran.
  auto r = test::run_command(render_cmd("--backend auto" + out));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // "note: auto: ..." where Vulkan is built in; without it the note names that first ("note:
  // backend 'vulkan': no Vulkan device (built without Vulkan); auto: using the cpu backend").
  EXPECT_EQ(r.output.rfind("note: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("auto: "), std::string::npos) << r.output;
  std::string ran = read_json_file((dir / "b.json").string())["device"]["backend"];
  EXPECT_TRUE(ran == "cpu" || ran == "vulkan") << ran;
  std::string reason;
  if (list_vulkan_devices(&reason).empty()) {
    // vulkan without a device is one line naming the reason.
    expect_one_line_error(test::run_command(render_cmd("--backend vulkan" + out + " -q")),
                          "backend 'vulkan': no Vulkan device");
  } else {
    auto v = test::run_command(render_cmd("--backend vulkan" + out + " -q"));
    ASSERT_EQ(v.exit_code, 0) << v.output;
    EXPECT_EQ(read_json_file((dir / "b.json").string())["device"]["backend"], "vulkan");
    expect_one_line_error(test::run_command(render_cmd("--backend vulkan --device 99" + out + " -q")),
                          "backend 'vulkan': device 99 does not exist");
  }
  expect_one_line_error(test::run_command(render_cmd("--backend metal" + out + " -q")), "valid: cpu, vulkan, auto");
}

}  // namespace
}  // namespace sst

#include "core/vpl/vpl_ply.h"

namespace sst {
namespace {
TEST(SstRender, ExportsTheVplSetAsPly) {
  auto dir = test::temp_dir();
  auto ply = (dir / "vpls.ply").string();
  auto r = test::run_command(render_cmd("--method uniform --vpls 300 --export-vpls " + ply + " --width 8 --spp 1 -q -o " +
                                        (dir / "u.exr").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_vpls_ply(ply).size(), 300u);
  nlohmann::json rec = read_json_file((dir / "u.json").string());
  EXPECT_EQ(rec["method_params"]["vpls"], 300);
  EXPECT_TRUE(rec["timings_ms"].contains("vpl_generation"));
}
}  // namespace
}  // namespace sst

namespace sst {
namespace {

TEST(SstRender, SequenceWritesNumberedFramesWithMotionARecordAndAPreview) {
  auto dir = test::temp_dir();
  std::ofstream(dir / "paths.json") << R"({"paths": [{"camera": "", "keys": [{"time": 0}, {"time": 1, "yaw_degrees": 20}]}]})";
  auto r = test::run_command(render_cmd("-o " + (dir / "seq.exr").string() + " --width 24 --height 24 --spp 1 --frames 3 " +
                                        "--frame-start 5 --temporal --denoise atrous --paths " +
                                        (dir / "paths.json").string() + " -q"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (int i : {5, 6, 7}) {
    std::string frame = (dir / ("seq_000" + std::to_string(i) + ".exr")).string();
    ASSERT_TRUE(std::filesystem::exists(frame)) << frame;
    std::vector<std::string> layers = list_layers(frame);
    for (const char* layer : {"motion", "raw", "albedo", "depth"})
      EXPECT_NE(std::find(layers.begin(), layers.end(), layer), layers.end()) << layer;
    EXPECT_EQ(read_layer(frame, "motion").channels, 2);
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "seq_0004.exr"));
  nlohmann::json rec = read_json_file((dir / "seq.json").string());
  ASSERT_EQ(rec["frames"].size(), 3u);
  EXPECT_EQ(rec["frames"][0]["index"], 5);
  EXPECT_NE(rec["frames"][0]["seed"], rec["frames"][1]["seed"]);
  EXPECT_TRUE(rec["frames"][2]["timings_ms"].contains("denoise"));
  ASSERT_TRUE(rec["frames"][2].contains("method_counters"));
  EXPECT_EQ(rec["frames"][2]["method_counters"], rec["method_counters"]);  // the last frame's
  EXPECT_EQ(rec["options"]["frames"], 3);
  // The preview needs ffmpeg; without it the record says why there is none.
  if (rec["outputs"].contains("preview"))
    EXPECT_GT(std::filesystem::file_size(dir / "seq.mp4"), 0u);
  else
    EXPECT_TRUE(rec.contains("warnings")) << rec.dump();
  EXPECT_FALSE(std::filesystem::exists(dir / "seq.preview-frames"));
}

TEST(SstRender, BadSequenceInputIsOneLineAndNonZeroExit) {
  auto dir = test::temp_dir();
  std::string out = " -o " + (dir / "x.exr").string() + " --width 8 --spp 1 -q";
  expect_one_line_error(test::run_command(render_cmd("--frames 0" + out)), "frames");
  expect_one_line_error(test::run_command(render_cmd("--denoise blur --frames 2" + out)), "denoise");
  expect_one_line_error(test::run_command(render_cmd("--indirect-scale 0" + out)), "indirect_scale");
  expect_one_line_error(test::run_command(render_cmd("--history-cap 0 --temporal" + out)), "history_cap");
  std::ofstream(dir / "p.json") << R"([{"camera": "nope", "keys": [{"time": 0}]}])";
  expect_one_line_error(test::run_command(render_cmd("--frames 2 --paths " + (dir / "p.json").string() + out)),
                        "no camera 'nope'");
  expect_one_line_error(test::run_command(render_cmd("--frames 2 --repeat 2" + out)), "--repeat");
  EXPECT_FALSE(std::filesystem::exists(dir / "x_0000.exr"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));
}

}  // namespace
}  // namespace sst
