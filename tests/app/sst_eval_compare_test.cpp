#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/image/image.h"
#include "core/metrics/flip.h"
#include "core/metrics/metrics.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using sst::Image;

namespace {

Image gradient(int w, int h, float offset) {
  Image im(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      im.set_rgb(x, y, sst::vec3(float(x) / w, float(y) / h, 0.5f) + offset * float((x * 7 + y * 3) % 5));
  return im;
}

sst::test::CommandResult eval(const std::string& arguments) {
  return sst::test::run_command(std::string(SST_EVAL_EXE) + " " + arguments);
}

// Appends rather than chains operator+: GCC 12 warns falsely (-Wrestrict) on "'" + string.
std::string quoted(const fs::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}

// "error: ..." on exactly one line.
void expect_one_error_line(const sst::test::CommandResult& r, const std::string& must_name) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_EQ(r.output.rfind("error: ", 0), 0u) << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
  EXPECT_NE(r.output.find(must_name), std::string::npos) << r.output;
}

struct Pair {
  fs::path test, reference;
};

Pair write_pair(const fs::path& dir, const std::string& ext) {
  Pair p{dir / ("test" + ext), dir / ("ref" + ext)};
  sst::write_image(p.test.string(), gradient(24, 16, 0.01f));
  sst::write_image(p.reference.string(), gradient(24, 16, 0.0f));
  return p;
}

}  // namespace

TEST(SstEvalCompare, JsonIsOneParseableObjectWithTheLibraryMetrics) {
  const Pair p = write_pair(sst::test::temp_dir(), ".exr");
  const auto r = eval("compare " + quoted(p.test) + " " + quoted(p.reference) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);  // throws, failing the test, if not one object
  ASSERT_TRUE(j.is_object());
  const sst::ImageMetrics m =
      sst::compare_images(sst::read_image(p.test.string()), sst::read_image(p.reference.string()));
  EXPECT_DOUBLE_EQ(j.at("rmse").get<double>(), m.rmse);
  EXPECT_DOUBLE_EQ(j.at("ssim").get<double>(), m.ssim);
  EXPECT_GT(m.rmse, 0.0);
  EXPECT_EQ(j.at("test").get<std::string>(), p.test.string());
  EXPECT_TRUE(j.at("layer").is_null());
}

TEST(SstEvalCompare, TableNamesEveryMetric) {
  const Pair p = write_pair(sst::test::temp_dir(), ".exr");
  const auto r = eval("compare " + quoted(p.test) + " " + quoted(p.reference));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* word : {"rmse", "rel_mse", "psnr", "ssim", "mean_test", "mean_ref"})
    EXPECT_NE(r.output.find(word), std::string::npos) << word << " missing in\n" << r.output;
}

TEST(SstEvalCompare, FlipIsPrintedBesideTheOtherMetricsAndItsMapsWritten) {
  const fs::path dir = sst::test::temp_dir();
  const Pair p = write_pair(dir, ".exr");
  const fs::path ldr_map = dir / "flip.png", hdr_map = dir / "flip_hdr.exr";
  const auto r = eval("compare " + quoted(p.test) + " " + quoted(p.reference) + " --json --flip-map " + quoted(ldr_map) +
                      " --flip-hdr-map " + quoted(hdr_map));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  const Image test = sst::read_image(p.test.string()), reference = sst::read_image(p.reference.string());
  EXPECT_DOUBLE_EQ(j.at("flip_ldr").get<double>(), sst::flip_ldr(test, reference).mean);
  EXPECT_DOUBLE_EQ(j.at("flip_hdr").get<double>(), sst::flip_hdr(test, reference).mean);
  EXPECT_GT(j.at("flip_ldr").get<double>(), 0.0);
  // The EXR holds the map's values: their mean is the reported one.
  const Image map = sst::read_image(hdr_map.string());
  double sum = 0.0;
  for (size_t i = 0; i < map.pixel_count(); ++i) sum += map.data[i * 3];
  EXPECT_NEAR(sum / double(map.pixel_count()), j.at("flip_hdr").get<double>(), 1e-6);
  EXPECT_EQ(sst::read_image(ldr_map.string()).width, 24);
  const auto table = eval("compare " + quoted(p.test) + " " + quoted(p.reference));
  for (const char* word : {"flip_ldr", "flip_hdr"})
    EXPECT_NE(table.output.find(word), std::string::npos) << word << " missing in\n" << table.output;
  // Two PNGs are display images: LDR-FLIP only.
  const Pair png = write_pair(dir, ".png");
  const nlohmann::json pj =
      nlohmann::json::parse(eval("compare " + quoted(png.test) + " " + quoted(png.reference) + " --json").output);
  EXPECT_TRUE(pj.at("flip_ldr").is_number());
  EXPECT_TRUE(pj.at("flip_hdr").is_null());
  expect_one_error_line(eval("compare " + quoted(png.test) + " " + quoted(png.reference) + " --flip-hdr-map " +
                             quoted(dir / "x.png")),
                        "HDR-FLIP");
}

TEST(SstEvalCompare, MissingFileIsOneErrorLineNamingIt) {
  const fs::path dir = sst::test::temp_dir();
  const Pair p = write_pair(dir, ".exr");
  const fs::path missing = dir / "missing.exr";
  expect_one_error_line(eval("compare " + quoted(missing) + " " + quoted(p.reference)), missing.string());
  expect_one_error_line(eval("compare " + quoted(p.test) + " " + quoted(missing) + " --json"),
                        missing.string());
}

TEST(SstEvalCompare, MismatchedSizesIsOneErrorLineNamingBothFiles) {
  const fs::path dir = sst::test::temp_dir();
  sst::write_image((dir / "small.exr").string(), gradient(12, 8, 0.0f));
  sst::write_image((dir / "large.png").string(), gradient(24, 16, 0.0f));
  const auto r = eval("compare " + quoted(dir / "small.exr") + " " + quoted(dir / "large.png"));
  expect_one_error_line(r, (dir / "small.exr").string());
  EXPECT_NE(r.output.find((dir / "large.png").string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("12x8"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("24x16"), std::string::npos) << r.output;
}

TEST(SstEvalCompare, LayerComparesThatLayerOnly) {
  const fs::path dir = sst::test::temp_dir();
  const Image rgb = gradient(16, 12, 0.0f);
  sst::write_image((dir / "a.exr").string(), rgb, {{"indirect", gradient(16, 12, 0.05f)}});
  sst::write_image((dir / "b.exr").string(), rgb, {{"indirect", gradient(16, 12, 0.0f)}});
  const std::string files = quoted(dir / "a.exr") + " " + quoted(dir / "b.exr");
  const auto whole = eval("compare " + files + " --json");
  const auto layer = eval("compare " + files + " --json --layer indirect");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  ASSERT_EQ(layer.exit_code, 0) << layer.output;
  EXPECT_EQ(nlohmann::json::parse(whole.output).at("rmse").get<double>(), 0.0);
  EXPECT_GT(nlohmann::json::parse(layer.output).at("rmse").get<double>(), 0.0);
  EXPECT_EQ(nlohmann::json::parse(layer.output).at("layer").get<std::string>(), "indirect");
  expect_one_error_line(eval("compare " + files + " --layer albedo"), "albedo");
}

TEST(SstEvalCompare, HeatmapIsWritten) {
  const fs::path dir = sst::test::temp_dir();
  const Pair p = write_pair(dir, ".exr");
  const fs::path heat = dir / "maps" / "error.png";
  const auto r = eval("compare " + quoted(p.test) + " " + quoted(p.reference) + " --heatmap " + quoted(heat));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Image map = sst::read_image(heat.string());
  EXPECT_EQ(map.width, 24);
  EXPECT_EQ(map.height, 16);
}

TEST(SstEvalCompare, PngPairIsComparedOnStoredLevels) {
  const Pair p = write_pair(sst::test::temp_dir(), ".png");
  const auto r = eval("compare " + quoted(p.test) + " " + quoted(p.reference) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double expected =
      sst::ssim(sst::read_image_stored(p.test.string()), sst::read_image_stored(p.reference.string()));
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(r.output).at("ssim").get<double>(), expected);
}

TEST(SstEvalCompare, UsageErrorsExitTwo) {
  EXPECT_EQ(eval("compare only-one.exr").exit_code, 2);
  EXPECT_EQ(eval("").exit_code, 2);
  EXPECT_EQ(eval("compare a.exr b.exr --no-such-flag").exit_code, 2);
}
