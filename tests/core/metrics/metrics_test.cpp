#include "core/metrics/metrics.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/util/error.h"
#include "tests/data/formula_images.h"
#include "tests/test_util.h"

using sst::Image;

namespace {

// The images of tests/data/make_ssim_goldens.py, rebuilt bit for bit: each value is computed in
// double and rounded to float, as numpy does when it stores into a float32 array.
using sst::test::formula::hash01;

double pattern(int x, int y, int c) {
  return 0.5 + 0.45 * std::sin(0.37 * x + 0.23 * y + 1.1 * c) * std::cos(0.19 * y - 0.11 * x + 0.5 * c);
}
double noisy(int x, int y, int c) {
  return std::clamp(pattern(x, y, c) + 0.3 * (hash01(x, y, c, 7) - 0.5), 0.0, 1.0);
}
double contrast(int x, int y, int c) { return 0.7 * pattern(x, y, c) + 0.1 + 0.05 * std::sin(0.5 * x); }
double linear_a(int x, int y, int c) { return 1.6 * std::pow(pattern(x, y, c), 2.0) - 0.2; }
double linear_b(int x, int y, int c) { return linear_a(x, y, c) + 0.4 * (hash01(x, y, c, 11) - 0.5); }

Image make(int width, int height, const std::function<double(int, int, int)>& value) {
  Image im(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = float(value(x, y, c));
  return im;
}

// scikit-image 0.19.3 (tests/data/make_ssim_goldens.py).
constexpr double kGoldenPatternVsNoisy = 0.8263829789;
constexpr double kGoldenPatternVsContrast = 0.9398656337;
constexpr double kGoldenNoisyVsPattern11x14 = 0.8180068052;
constexpr double kGoldenMap000 = 0.8703165597;
constexpr double kGoldenMap39_31_2 = 0.7032516404;
constexpr double kGoldenMap2_20_1 = 0.8744940045;
constexpr double kGoldenLinearDisplay = 0.8155495475;
constexpr double kGoldenCornellPng = 0.8957650312;
constexpr double kGoldenCornellExrDisplay = 0.8973132610;
constexpr double kGoldenTolerance = 1e-4;

std::string error_of(const std::function<void()>& body) {
  try {
    body();
  } catch (const sst::Error& e) {
    return e.what();
  }
  return "(no sst::Error thrown)";
}

Image tiny(std::vector<float> values) {
  Image im(2, 1);
  im.data = std::move(values);
  return im;
}

}  // namespace

TEST(Metrics, HandComputedOnTinyImages) {
  const Image test = tiny({0.1f, 0.2f, 0.3f, 0.5f, 0.5f, 0.5f});
  const Image ref = tiny({0.1f, 0.1f, 0.1f, 0.5f, 0.7f, 0.5f});
  const sst::ImageMetrics m = sst::compare_images(test, ref);
  // Differences 0, .1, .2, 0, -.2, 0: squared sum .09 over 6 values.
  EXPECT_NEAR(m.rmse, std::sqrt(0.015), 1e-6);
  EXPECT_NEAR(m.rel_mse, (0.01 / 0.02 + 0.04 / 0.02 + 0.04 / 0.50) / 6.0, 1e-6);
  EXPECT_NEAR(m.psnr, 10.0 * std::log10(1.0 / 0.015), 1e-4);
  EXPECT_NEAR(m.mae, 0.5 / 6.0, 1e-6);
  EXPECT_NEAR(m.mean_test.x, 0.3, 1e-6);
  EXPECT_NEAR(m.mean_test.y, 0.35, 1e-6);
  EXPECT_NEAR(m.mean_test.z, 0.4, 1e-6);
  EXPECT_NEAR(m.mean_reference.y, 0.4, 1e-6);
  EXPECT_NEAR(m.mean_reference.z, 0.3, 1e-6);
  EXPECT_TRUE(std::isnan(m.ssim)) << "2x1 is smaller than the SSIM window";
  EXPECT_EQ(m.nonfinite_test, 0u);
}

// The masked errors leave out the pixels where the mask is non-zero, and only those.
TEST(Metrics, MaskedErrorsSkipThePixelsTheMaskMarks) {
  Image reference(4, 2), test(4, 2), mask(4, 2);
  for (float& v : reference.data) v = 0.5f;
  test = reference;
  test.set_rgb(1, 0, sst::vec3(10.0f));  // a visible emitter's error, masked
  mask.set_rgb(1, 0, sst::vec3(3.0f));
  mask.at(2, 1, 1) = 1.0f;          // one channel marks a pixel too
  test.set_rgb(3, 1, sst::vec3(0.5f + 0.3f, 0.5f, 0.5f));
  const sst::MaskedErrors e = sst::masked_errors(test, reference, mask);
  EXPECT_EQ(e.pixels, 6u);
  EXPECT_NEAR(e.rmse, std::sqrt(0.09 / 18.0), 1e-7);
  EXPECT_NEAR(e.mae, 0.3 / 18.0, 1e-7);
  EXPECT_NEAR(e.rel_mse, 0.09 / 0.26 / 18.0, 1e-7);
  EXPECT_THROW(sst::masked_errors(test, reference, Image(2, 2)), sst::Error);
}

TEST(Metrics, RelativeMseWeighsDarkPixelsMore) {
  // The same absolute error counts 50x more on a black reference than on a white one.
  const sst::ImageMetrics dark = sst::compare_images(tiny({0.1f, 0, 0, 0, 0, 0}), tiny({0, 0, 0, 0, 0, 0}));
  const sst::ImageMetrics bright = sst::compare_images(tiny({1.1f, 1, 1, 1, 1, 1}), tiny({1, 1, 1, 1, 1, 1}));
  EXPECT_NEAR(dark.rmse, bright.rmse, 1e-6);
  EXPECT_NEAR(dark.rel_mse, 0.01 / 0.01 / 6.0, 1e-6);
  EXPECT_NEAR(bright.rel_mse, 0.01 / 1.01 / 6.0, 1e-6);
}

TEST(Metrics, IdenticalImagesAreSsimOneAndInfinitePsnr) {
  const Image a = make(40, 32, noisy);
  const sst::ImageMetrics m = sst::compare_images(a, a);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.rel_mse, 0.0);
  EXPECT_TRUE(std::isinf(m.psnr));
  EXPECT_NEAR(m.ssim, 1.0, 1e-12);
  const nlohmann::json j = sst::to_json(m);
  EXPECT_TRUE(j.at("psnr").is_null());
  EXPECT_NEAR(j.at("ssim").get<double>(), 1.0, 1e-12);
}

TEST(Metrics, MismatchedSizesNameBothSizes) {
  const std::string message = error_of([] { sst::compare_images(Image(64, 48), Image(32, 32)); });
  EXPECT_NE(message.find("64x48"), std::string::npos) << message;
  EXPECT_NE(message.find("32x32"), std::string::npos) << message;
  EXPECT_NE(error_of([] { sst::ssim(Image(12, 12), Image(12, 12, 1)); }).find("12x12x1"), std::string::npos);
}

TEST(Metrics, NonFiniteTestPixelsAreCountedAndTreatedAsZero) {
  Image bad = make(20, 16, pattern), zeroed = bad;
  bad.at(3, 4, 1) = std::numeric_limits<float>::quiet_NaN();
  bad.at(5, 6, 0) = std::numeric_limits<float>::infinity();
  bad.at(5, 6, 2) = -std::numeric_limits<float>::infinity();
  zeroed.at(3, 4, 1) = zeroed.at(5, 6, 0) = zeroed.at(5, 6, 2) = 0.0f;
  const Image ref = make(20, 16, noisy);
  const sst::ImageMetrics m = sst::compare_images(bad, ref), expected = sst::compare_images(zeroed, ref);
  EXPECT_EQ(m.nonfinite_test, 2u);
  EXPECT_EQ(m.nonfinite_reference, 0u);
  EXPECT_EQ(m.rmse, expected.rmse);
  EXPECT_EQ(m.ssim, expected.ssim);
  EXPECT_TRUE(std::isfinite(m.rmse) && std::isfinite(m.ssim));
}

TEST(Metrics, DisplayInputsUseDecodedValuesForErrors) {
  const Image a = make(16, 16, pattern), b = make(16, 16, noisy);
  const sst::ImageMetrics display = sst::compare_images(a, b, true);
  const sst::ImageMetrics linear = sst::compare_images(sst::from_display(a), sst::from_display(b));
  EXPECT_NEAR(display.rmse, linear.rmse, 1e-6);
  EXPECT_NEAR(display.ssim, linear.ssim, 1e-5);
  EXPECT_NEAR(display.ssim, sst::ssim(a, b), 1e-12);
}

TEST(Metrics, JsonListsEveryField) {
  const sst::ImageMetrics m = sst::compare_images(make(16, 12, pattern), make(16, 12, noisy));
  const nlohmann::json j = sst::to_json(m);
  for (const char* key : {"width", "height", "rmse", "rel_mse", "psnr", "ssim", "mae", "mean_test",
                          "mean_reference", "nonfinite_test", "nonfinite_reference"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.at("width").get<int>(), 16);
  EXPECT_EQ(j.at("rmse").get<double>(), m.rmse);
  EXPECT_EQ(j.at("mean_reference").size(), 3u);
  EXPECT_EQ(j.at("mean_test")[2].get<double>(), m.mean_test.z);
}

TEST(MetricsSsim, MatchesScikitImageOnSyntheticImages) {
  EXPECT_NEAR(sst::ssim(make(40, 32, pattern), make(40, 32, noisy)), kGoldenPatternVsNoisy, kGoldenTolerance);
  EXPECT_NEAR(sst::ssim(make(40, 32, pattern), make(40, 32, contrast)), kGoldenPatternVsContrast,
              kGoldenTolerance);
  EXPECT_NEAR(sst::ssim(make(11, 14, noisy), make(11, 14, pattern)), kGoldenNoisyVsPattern11x14,
              kGoldenTolerance);
}

TEST(MetricsSsim, LinearInputsAreClampedAndEncodedFirst) {
  const Image a = make(40, 32, linear_a), b = make(40, 32, linear_b);
  EXPECT_NEAR(sst::compare_images(a, b).ssim, kGoldenLinearDisplay, kGoldenTolerance);
}

TEST(MetricsSsim, MapBorderFollowsScipyReflect) {
  const Image map = sst::ssim_map(make(40, 32, pattern), make(40, 32, noisy));
  EXPECT_NEAR(map.at(0, 0, 0), kGoldenMap000, 1e-6);
  EXPECT_NEAR(map.at(39, 31, 2), kGoldenMap39_31_2, 1e-6);
  EXPECT_NEAR(map.at(2, 20, 1), kGoldenMap2_20_1, 1e-6);
}

TEST(MetricsSsim, ImagesSmallerThanTheWindowHaveNoSsim) {
  EXPECT_TRUE(std::isnan(sst::ssim(make(10, 20, pattern), make(10, 20, noisy))));
  EXPECT_TRUE(std::isnan(sst::ssim(make(20, 10, pattern), make(20, 10, noisy))));
  EXPECT_FALSE(std::isnan(sst::ssim(make(11, 11, pattern), make(11, 11, noisy))));
  EXPECT_TRUE(sst::to_json(sst::compare_images(make(5, 5, pattern), make(5, 5, noisy))).at("ssim").is_null());
}

TEST(MetricsSsim, SameBitsWhateverTheThreadCount) {
  const Image a = make(200, 120, pattern), b = make(200, 120, noisy);
  double one_thread = 0.0;
  tbb::task_arena(1).execute([&] { one_thread = sst::ssim(a, b); });
  EXPECT_EQ(sst::ssim(a, b), one_thread);
}

// Its time is printed, not asserted: a sanitizer build runs it several times slower.
TEST(MetricsSsim, FullHdIdenticalIsOne) {
  const Image a = make(1280, 720, noisy);
  const auto start = std::chrono::steady_clock::now();
  const double s = sst::ssim(a, a);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NEAR(s, 1.0, 1e-12);
  std::printf("ssim 1280x720: %.1f ms\n", ms);
}

TEST(MetricsSsim, CornellPngPairMatchesScikitImage) {
  const auto test = sst::test::shared_scene("cornell-box/ref/cornell-box_256spp_seed2.png");
  const auto ref = sst::test::shared_scene("cornell-box/ref/cornell-box_4096spp_seed1.png");
  if (test.empty() || ref.empty()) GTEST_SKIP() << "shared scenes not present";
  const Image a = sst::read_image_stored(test.string()), b = sst::read_image_stored(ref.string());
  EXPECT_NEAR(sst::ssim(a, b), kGoldenCornellPng, kGoldenTolerance);
  EXPECT_NEAR(sst::compare_images(a, b, true).ssim, kGoldenCornellPng, kGoldenTolerance);
}

TEST(MetricsSsim, CornellExrPairMatchesScikitImage) {
  const auto test = sst::test::shared_scene("cornell-box/ref/cornell-box_256spp_seed2.exr");
  const auto ref = sst::test::shared_scene("cornell-box/ref/cornell-box_4096spp_seed1.exr");
  if (test.empty() || ref.empty()) GTEST_SKIP() << "shared scenes not present";
  const Image a = sst::read_image(test.string()), b = sst::read_image(ref.string());
  EXPECT_NEAR(sst::compare_images(a, b).ssim, kGoldenCornellExrDisplay, kGoldenTolerance);
}

TEST(MetricsErrorMap, RelativeAndSquaredErrorHandComputed) {
  const Image test = tiny({0.3f, 0.3f, 0.3f, 1.0f, 0.0f, 0.5f});
  const Image ref = tiny({0.1f, 0.1f, 0.1f, 0.5f, 0.5f, 0.5f});
  const Image rel = sst::relative_error_image(test, ref);
  ASSERT_EQ(rel.channels, 1);
  EXPECT_NEAR(rel.data[0], 0.2 / 0.11, 1e-5);
  EXPECT_NEAR(rel.data[1], (1.0 / 3.0) / 0.51, 1e-5);
  const Image se = sst::squared_error_image(test, ref);
  ASSERT_EQ(se.channels, 3);
  EXPECT_NEAR(se.data[0], 0.04, 1e-6);
  EXPECT_NEAR(se.data[4], 0.25, 1e-6);
  EXPECT_EQ(se.data[5], 0.0f);
}

TEST(MetricsErrorMap, HeatmapWritesTheColormapsColours) {
  const Image ref = make(4, 4, pattern);
  Image test = ref;
  test.set_rgb(1, 1, ref.rgb(1, 1) * 100.0f);  // far beyond max_error
  const Image heat = sst::error_heatmap(test, ref, 0.5f);
  const Image display = sst::to_display(heat);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(display.at(0, 0, c), sst::inferno(0.0f)[c], 1e-5) << "no error -> darkest colour";
    EXPECT_NEAR(display.at(1, 1, c), sst::inferno(1.0f)[c], 1e-5) << "saturated -> brightest colour";
  }
  EXPECT_LT(sst::luminance(sst::inferno(0.0f)), sst::luminance(sst::inferno(0.5f)));
  EXPECT_LT(sst::luminance(sst::inferno(0.5f)), sst::luminance(sst::inferno(1.0f)));
}
