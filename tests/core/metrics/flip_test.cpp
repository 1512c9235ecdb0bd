#include "core/metrics/flip.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/metrics/error_map.h"
#include "core/util/error.h"
#include "tests/data/formula_images.h"

using sst::FlipOptions;
using sst::Image;

namespace {

using sst::test::formula::hash01;
constexpr auto* ldr_reference = &sst::test::formula::flip_ldr_reference;
constexpr auto* ldr_test = &sst::test::formula::flip_ldr_test;
constexpr auto* hdr_reference = &sst::test::formula::flip_hdr_reference;
constexpr auto* hdr_test = &sst::test::formula::flip_hdr_test;

Image make(const std::function<double(int, int, int)>& value, int width = 64, int height = 48) {
  Image im(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) im.at(x, y, c) = float(value(x, y, c));
  return im;
}

Image uniform(std::array<double, 3> rgb, int size = 8) {
  return make([&](int, int, int c) { return rgb[c]; }, size, size);
}

// NVIDIA's reference implementation of FLIP on the images above (tests/data/make_flip_goldens.cpp,
// NVlabs/flip v1.6): the mean of its map, its HDR exposure range, and pixels of its maps.
constexpr double kGoldenLdrMean = 0.170184560;
constexpr double kGoldenHdrMean = 0.176286258;
constexpr double kGoldenStartExposure = -4.519468, kGoldenStopExposure = 4.329745;
constexpr int kGoldenExposures = 9;
struct GoldenPixel {
  int x, y;
  double value;
};
constexpr GoldenPixel kGoldenLdrPixels[] = {
    {1, 19, 0.018755041}, {27, 15, 0.039603341}, {45, 20, 0.310988724}, {46, 20, 0.354395092}, {10, 35, 0.268015593}};
constexpr GoldenPixel kGoldenHdrPixels[] = {
    {12, 10, 0.064107999}, {10, 8, 0.091461219}, {30, 30, 0.132549062}, {2, 45, 0.039622571}, {50, 20, 0.122773305}};
// Both implementations work in float32 with different orders of summation and different colour
// matrices (rational vs. derived from the primaries). Over all 3072 pixels of either map the two
// differ by at most 5.2e-6 (measured), and a mean differs by no more than its largest pixel
// difference: 1e-5 leaves a factor two. The exposures are logarithms of float ratios.
constexpr double kGoldenTolerance = 1e-5;
constexpr double kExposureTolerance = 1e-5;

FlipOptions keeping_map() {
  FlipOptions o;
  o.keep_map = true;
  return o;
}

FlipOptions fixed_exposures(double start, double stop, int count) {
  FlipOptions o;
  o.start_exposure = start;
  o.stop_exposure = stop;
  o.exposures = count;
  return o;
}

// CIELab with the Hunt adjustment, from the IEC 61966-2-1 sRGB matrix and its D65 white (the
// code derives its matrix from the primaries instead: the two agree to about 1e-4).
std::array<double, 3> hunt_lab(std::array<double, 3> rgb) {
  const double m[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
  std::array<double, 3> f;
  for (int i = 0; i < 3; ++i) {
    const double white = m[i][0] + m[i][1] + m[i][2];
    const double t = (m[i][0] * rgb[0] + m[i][1] * rgb[1] + m[i][2] * rgb[2]) / white;
    const double d = 6.0 / 29.0;
    f[i] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
  }
  const double l = 116 * f[1] - 16;
  return {l, 0.01 * l * 500 * (f[0] - f[1]), 0.01 * l * 200 * (f[1] - f[2])};
}

double hyab(std::array<double, 3> p, std::array<double, 3> q) {
  return std::abs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// The colour term of FLIP for two uniform colours, straight from the paper's formulas.
double expected_uniform_flip(std::array<double, 3> a, std::array<double, 3> b) {
  const double cmax = std::pow(hyab(hunt_lab({0, 1, 0}), hunt_lab({0, 0, 1})), 0.7), pccmax = 0.4 * cmax;
  const double e = std::pow(hyab(hunt_lab(a), hunt_lab(b)), 0.7);
  return e < pccmax ? e * 0.95 / pccmax : 0.95 + (e - pccmax) / (cmax - pccmax) * 0.05;
}

double aces(double x) {
  const double a = 0.6 * 0.6 * 2.51, b = 0.6 * 0.03, c = 0.6 * 0.6 * 2.43, d = 0.6 * 0.59, e = 0.14;
  return (a * x * x + b * x) / (c * x * x + d * x + e);
}

// Where the ACES curve reaches 0.85, by bisection (the code solves the quadratic).
double aces_x85() {
  double lo = 0.0, hi = 100.0;
  for (int i = 0; i < 200; ++i) (aces(0.5 * (lo + hi)) < 0.85 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(Flip, DefaultPpdIsTheFourKMonitorAtArmsLength) {
  // 0.7 m * (3840 px / 0.7 m) * pi / 180: 67.02 pixels per degree.
  EXPECT_NEAR(sst::kFlipDefaultPpd, 67.0206, 1e-4);
  EXPECT_EQ(FlipOptions{}.ppd, sst::kFlipDefaultPpd);
}

TEST(Flip, IdenticalImagesGiveZero) {
  for (const Image& im : {make(ldr_reference), make(hdr_reference), make(ldr_test)}) {
    const sst::FlipResult ldr = sst::flip_ldr(im, im, keeping_map()), hdr = sst::flip_hdr(im, im, keeping_map());
    EXPECT_EQ(ldr.mean, 0.0);
    EXPECT_EQ(hdr.mean, 0.0);
    EXPECT_EQ(*std::max_element(ldr.map.data.begin(), ldr.map.data.end()), 0.0f);
    EXPECT_EQ(*std::max_element(hdr.map.data.begin(), hdr.map.data.end()), 0.0f);
  }
}

TEST(Flip, LdrMatchesNvidiasReferenceImplementation) {
  const sst::FlipResult r = sst::flip_ldr(make(ldr_test), make(ldr_reference), keeping_map());
  EXPECT_NEAR(r.mean, kGoldenLdrMean, kGoldenTolerance);
  ASSERT_EQ(r.map.channels, 1);
  for (const GoldenPixel& p : kGoldenLdrPixels)
    EXPECT_NEAR(r.map.at(p.x, p.y, 0), p.value, kGoldenTolerance) << p.x << "," << p.y;
}

TEST(Flip, HdrMatchesNvidiasReferenceImplementation) {
  const sst::FlipResult r = sst::flip_hdr(make(hdr_test), make(hdr_reference), keeping_map());
  EXPECT_NEAR(r.mean, kGoldenHdrMean, kGoldenTolerance);
  EXPECT_NEAR(r.start_exposure, kGoldenStartExposure, kExposureTolerance);
  EXPECT_NEAR(r.stop_exposure, kGoldenStopExposure, kExposureTolerance);
  EXPECT_EQ(r.exposures, kGoldenExposures);
  for (const GoldenPixel& p : kGoldenHdrPixels)
    EXPECT_NEAR(r.map.at(p.x, p.y, 0), p.value, kGoldenTolerance) << p.x << "," << p.y;
}

// Uniform images have no features and pass the normalised filters unchanged: FLIP is the
// remapped HyAB of the two colours alone, so a shift larger in HyAB is a larger FLIP.
TEST(Flip, UniformColoursGiveTheRemappedHyAB) {
  const std::array<double, 3> grey = {0.4, 0.4, 0.4};
  std::vector<std::array<double, 3>> shifted = {{0.42, 0.4, 0.4},  {0.4, 0.4, 0.45}, {0.5, 0.4, 0.4},
                                                {0.4, 0.55, 0.4},  {0.3, 0.3, 0.6},  {0.8, 0.1, 0.1},
                                                {0.0, 0.0, 0.0},   {1.0, 1.0, 1.0},  {0.41, 0.41, 0.41}};
  std::sort(shifted.begin(), shifted.end(),
            [&](const auto& a, const auto& b) { return hyab(hunt_lab(a), hunt_lab(grey)) < hyab(hunt_lab(b), hunt_lab(grey)); });
  double previous = 0.0;
  for (const auto& s : shifted) {
    const double flip = sst::flip_ldr(uniform(s), uniform(grey)).mean;
    // The two colour matrices differ by about 1e-4 (relative), and the features of a uniform
    // image are zero only up to float rounding in the derivative filters: measured differences
    // are below 9e-5.
    EXPECT_NEAR(flip, expected_uniform_flip(s, grey), 3e-4) << s[0] << " " << s[1] << " " << s[2];
    EXPECT_GT(flip, previous) << s[0] << " " << s[1] << " " << s[2];
    previous = flip;
  }
}

// The remapping sends the gamut's largest HyAB, pure green against pure blue, to 1: every pair of
// displayable colours stays within [0,1], however strong its features.
TEST(Flip, ErrorIsWithinZeroAndOne) {
  EXPECT_NEAR(sst::flip_ldr(uniform({0, 1, 0}), uniform({0, 0, 1})).mean, 1.0, 1e-6);
  std::vector<std::array<double, 3>> colours;
  for (double r : {0.0, 0.5, 1.0})
    for (double g : {0.0, 0.5, 1.0})
      for (double b : {0.0, 0.5, 1.0}) colours.push_back({r, g, b});
  double largest = 0.0;
  for (size_t i = 0; i < colours.size(); ++i)
    for (size_t j = i + 1; j < colours.size(); ++j) {
      const double flip = sst::flip_ldr(uniform(colours[i], 1), uniform(colours[j], 1)).mean;
      EXPECT_GE(flip, 0.0);
      EXPECT_LE(flip, 1.0);
      largest = std::max(largest, flip);
    }
  EXPECT_GT(largest, 0.99);
  // One-pixel checkerboards of green and blue against their inverse: the largest colour error
  // and the strongest points at every pixel.
  const Image a = make([](int x, int y, int c) { return ((x + y) % 2 == 0) == (c == 1) ? 1.0 : 0.0; }, 16, 16);
  const Image b = make([](int x, int y, int c) { return ((x + y) % 2 == 1) == (c == 1) ? 1.0 : 0.0; }, 16, 16);
  for (const sst::FlipResult& r : {sst::flip_ldr(a, b, keeping_map()), sst::flip_hdr(a, b, keeping_map())})
    for (float v : r.map.data) {
      EXPECT_GE(v, 0.0f);
      EXPECT_LE(v, 1.0f);
    }
}

// Every step is the same for both images and they meet only in symmetric differences (|dL|,
// |dab|, |d edge|, |d point|), so LDR-FLIP is symmetric; HDR-FLIP takes its exposure range from
// the reference, and is not.
TEST(Flip, LdrIsSymmetricHdrOnlyForFixedExposures) {
  const Image a = make(ldr_test), b = make(ldr_reference);
  const sst::FlipResult ab = sst::flip_ldr(a, b, keeping_map()), ba = sst::flip_ldr(b, a, keeping_map());
  EXPECT_EQ(ab.mean, ba.mean);
  EXPECT_EQ(ab.map.data, ba.map.data);
  const Image t = make(hdr_test), r = make(hdr_reference);
  EXPECT_NE(sst::flip_hdr(t, r).exposures, sst::flip_hdr(r, t).exposures);
  EXPECT_GT(std::abs(sst::flip_hdr(t, r).mean - sst::flip_hdr(r, t).mean), 1e-4);  // rounding: about 1e-7
  const FlipOptions fixed = fixed_exposures(-3.0, 2.0, 6);
  EXPECT_EQ(sst::flip_hdr(t, r, fixed).mean, sst::flip_hdr(r, t, fixed).mean);
}

TEST(Flip, GrowsWithTheNoiseAmplitude) {
  const Image reference = make(ldr_reference);
  const Image hdr_ref = make(hdr_reference);
  double previous_ldr = 0.0, previous_hdr = 0.0;
  for (double amplitude : {0.01, 0.03, 0.1, 0.3}) {
    const Image noisy = make([&](int x, int y, int c) { return ldr_reference(x, y, c) + amplitude * (hash01(x, y, c, 21) - 0.5); });
    const Image hdr_noisy =
        make([&](int x, int y, int c) { return hdr_reference(x, y, c) * (1.0 + 2.0 * amplitude * (hash01(x, y, c, 22) - 0.5)); });
    const double ldr = sst::flip_ldr(noisy, reference).mean, hdr = sst::flip_hdr(hdr_noisy, hdr_ref).mean;
    EXPECT_GT(ldr, previous_ldr) << amplitude;
    EXPECT_GT(hdr, previous_hdr) << amplitude;
    previous_ldr = ldr, previous_hdr = hdr;
  }
}

// More pixels per degree (the observer farther away) filters more of fine noise away.
TEST(Flip, FineNoiseFadesWithMorePixelsPerDegree) {
  const Image reference = uniform({0.4, 0.4, 0.4}, 48);
  const Image noisy = make([](int x, int y, int c) { return 0.4 + 0.3 * (hash01(x, y, c, 31) - 0.5); }, 48, 48);
  double previous = 1.0;
  for (double ppd : {15.0, 30.0, sst::kFlipDefaultPpd, 120.0}) {
    FlipOptions o;
    o.ppd = ppd;
    const double flip = sst::flip_ldr(noisy, reference, o).mean;
    EXPECT_LT(flip, previous) << ppd;
    previous = flip;
  }
}

// LDR-FLIP sees linear values as a display shows them: clamped to [0,1].
TEST(Flip, LdrClampsLinearValuesToTheDisplayRange) {
  const Image reference = make(ldr_reference);
  const Image bright = make([](int x, int y, int c) { return 1.0 + 3.0 * ldr_reference(x, y, c); });
  const Image negative = make([](int x, int y, int c) { return -ldr_reference(x, y, c); });
  EXPECT_EQ(sst::flip_ldr(bright, reference).mean, sst::flip_ldr(make([](int, int, int) { return 1.0; }), reference).mean);
  EXPECT_EQ(sst::flip_ldr(negative, reference).mean, sst::flip_ldr(make([](int, int, int) { return 0.0; }), reference).mean);
  EXPECT_GT(sst::flip_ldr(bright, reference).mean, 0.1);
}

TEST(Flip, HdrWithOneExposureAtZeroIsLdrOfTheToneMappedImages) {
  const Image t = make(hdr_test), r = make(hdr_reference);
  auto tone_mapped = [](const Image& im) {
    Image out = im;
    for (float& v : out.data) v = float(std::clamp(aces(v), 0.0, 1.0));
    return out;
  };
  const sst::FlipResult hdr = sst::flip_hdr(t, r, fixed_exposures(0.0, 0.0, 1));
  EXPECT_EQ(hdr.exposures, 1);
  EXPECT_NEAR(hdr.mean, sst::flip_ldr(tone_mapped(t), tone_mapped(r)).mean, 1e-6);
  // And it is the maximum over its exposures: never below any one of them.
  const sst::FlipResult many = sst::flip_hdr(t, r, fixed_exposures(-2.0, 2.0, 5));
  EXPECT_GT(many.mean, hdr.mean);
  for (float x : {0.0f, 0.01f, 0.18f, 1.0f, 10.0f}) EXPECT_NEAR(sst::flip_aces(x), aces(x), 1e-6) << x;
}

// The start exposure brings the reference's largest luminance, the stop its median, to where the
// tone mapper gives 0.85; one exposure per stop, at least two.
TEST(Flip, ExposureRangeComesFromTheReference) {
  const double x85 = aces_x85();
  // Grey pixels (luminance = value): 0.25 in over half, 16 at the brightest.
  Image r = make([](int x, int y, int) { return x < 40 ? 0.25 : (x == 63 && y == 0 ? 16.0 : 2.0); });
  sst::FlipResult res = sst::flip_hdr(r, r);
  EXPECT_NEAR(res.start_exposure, std::log2(x85 / 16.0), 1e-5);
  EXPECT_NEAR(res.stop_exposure, std::log2(x85 / 0.25), 1e-5);
  EXPECT_EQ(res.exposures, int(std::ceil(std::log2(16.0 / 0.25))));
  // Over half black: the darkest lit pixel stands in for the median, and nothing is infinite.
  r = make([](int x, int, int) { return x < 40 ? 0.0 : (x < 63 ? 0.5 : 4.0); });
  res = sst::flip_hdr(r, r);
  EXPECT_NEAR(res.stop_exposure, std::log2(x85 / 0.5), 1e-5);
  EXPECT_NEAR(res.start_exposure, std::log2(x85 / 4.0), 1e-5);
  EXPECT_EQ(res.exposures, 3);
  // All black: one place to look, at exposure 0.
  res = sst::flip_hdr(uniform({0.1, 0.2, 0.3}), uniform({0, 0, 0}));
  EXPECT_EQ(res.start_exposure, 0.0);
  EXPECT_EQ(res.stop_exposure, 0.0);
  EXPECT_GT(res.mean, 0.0);
  EXPECT_THROW(sst::flip_hdr(r, r, fixed_exposures(1.0, -1.0, 3)), sst::Error);
  EXPECT_THROW(sst::flip_hdr(r, r, fixed_exposures(-1.0, 1.0, 1)), sst::Error);
}

TEST(Flip, NonFiniteInputsNeverReachTheOutput) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  Image t = make(hdr_test), r = make(hdr_reference);
  t.at(3, 3, 0) = nan, t.at(20, 30, 1) = inf, t.at(21, 30, 2) = -inf, t.at(40, 40, 0) = 3e38f;
  r.at(50, 5, 1) = nan, r.at(51, 5, 0) = inf;
  for (const sst::FlipResult& res : {sst::flip_ldr(t, r, keeping_map()), sst::flip_hdr(t, r, keeping_map())}) {
    EXPECT_TRUE(std::isfinite(res.mean));
    EXPECT_TRUE(std::isfinite(res.start_exposure) && std::isfinite(res.stop_exposure));
    for (float v : res.map.data) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
  }
  // A NaN counts as 0: the same FLIP as a black pixel there.
  Image black = make(ldr_test), nan_pixel = black;
  black.at(10, 10, 0) = 0.0f, nan_pixel.at(10, 10, 0) = nan;
  EXPECT_EQ(sst::flip_ldr(nan_pixel, make(ldr_reference)).mean, sst::flip_ldr(black, make(ldr_reference)).mean);
}

TEST(Flip, RejectsMismatchedShapesAndOtherChannelCounts) {
  EXPECT_THROW(sst::flip_ldr(Image(8, 8), Image(8, 9)), sst::Error);
  EXPECT_THROW(sst::flip_hdr(Image(8, 8, 1), Image(8, 8, 1)), sst::Error);
  FlipOptions o;
  o.ppd = 0.0;
  EXPECT_THROW(sst::flip_ldr(Image(8, 8), Image(8, 8), o), sst::Error);
  EXPECT_EQ(sst::flip_ldr(Image(0, 0), Image(0, 0)).mean, 0.0);
}

TEST(Flip, MetricsJsonHasBothMeansAndNullsWithoutRgb) {
  const nlohmann::json j = sst::flip_metrics(make(hdr_test), make(hdr_reference));
  EXPECT_NEAR(j.at("flip_ldr").get<double>(), sst::flip_ldr(make(hdr_test), make(hdr_reference)).mean, 0.0);
  EXPECT_NEAR(j.at("flip_hdr").get<double>(), kGoldenHdrMean, kGoldenTolerance);
  const nlohmann::json grey = sst::flip_metrics(Image(8, 8, 1), Image(8, 8, 1));
  EXPECT_TRUE(grey.at("flip_ldr").is_null());
  EXPECT_TRUE(grey.at("flip_hdr").is_null());
}

TEST(Flip, HeatmapRunsFromBlackToPaleYellow) {
  Image map(2, 1, 1);
  map.data = {0.0f, 1.0f};
  const Image heat = sst::inferno_image(map);
  ASSERT_EQ(heat.channels, 3);
  EXPECT_LT(heat.at(0, 0, 0) + heat.at(0, 0, 1) + heat.at(0, 0, 2), 0.01f);
  EXPECT_GT(heat.at(1, 0, 0), 0.9f);
  EXPECT_GT(heat.at(1, 0, 1), 0.9f);
  EXPECT_LT(heat.at(1, 0, 2), heat.at(1, 0, 1));
}
