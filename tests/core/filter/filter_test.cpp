// The G-buffer-guided filters on the CPU (core/filter/filters.h): constant images pass unchanged,
// nothing crosses a depth edge, degenerate inputs stay finite, and the output does not depend on the
// thread count. (The mean of a rendered image through the filters: tests/core/pipeline.)
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <functional>

#include "core/filter/filters.h"
#include "core/util/error.h"
#include "tests/core/filter/filter_test_images.h"

namespace sst {
namespace {

using test::constant_image;
using test::point_downsample;
using test::single_frame_moments;
using test::two_planes;

// The three filters behind one signature: (colour, depth, normal) at full resolution in, filtered
// colour out. SVGF takes its moments from the one frame; upsampling takes `color` point-sampled at
// half resolution with the G-buffer sampled alike.
using Filter = std::function<Image(const Image& color, const Image& depth, const Image& normal)>;

Image run_atrous(const Image& color, const Image& depth, const Image& normal) {
  return atrous_filter(color, depth, normal, AtrousParams{});
}
Image run_svgf(const Image& color, const Image& depth, const Image& normal) {
  Image history = constant_image(color.width, color.height, 1, 1.0f);
  return svgf_spatial(color, single_frame_moments(color), history, depth, normal, SvgfParams{}).filtered;
}
Image run_upsample(const Image& color, const Image& depth, const Image& normal) {
  UpsampleParams params;
  const int scale = 2;
  return joint_bilateral_upsample(point_downsample(color, scale), point_downsample(depth, scale),
                                  point_downsample(normal, scale), depth, normal, params);
}

struct NamedFilter {
  const char* name;
  Filter run;
};
const NamedFilter kFilters[] = {{"atrous", run_atrous}, {"svgf", run_svgf}, {"upsample", run_upsample}};

double max_abs_difference(const Image& a, const Image& b) {
  double d = 0.0;
  for (size_t i = 0; i < a.data.size(); ++i) d = std::max(d, std::abs(double(a.data[i]) - double(b.data[i])));
  return d;
}

bool all_finite(const Image& image) {
  for (float v : image.data)
    if (!std::isfinite(v)) return false;
  return true;
}

// The mean of columns [x0, x1) over the rows that see a surface.
double band_mean(const Image& image, int x0, int x1, int first_row = 0) {
  double s = 0.0;
  size_t n = 0;
  for (int y = first_row; y < image.height; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < image.channels; ++c, ++n) s += image.at(x, y, c);
  return s / double(n);
}

TEST(Filters, LeaveAConstantImageUnchanged) {
  // A constant colour over two planes and a sky band: every weight is whatever it is, and the
  // normalised blend of equal values is that value.
  test::TwoPlanes t = two_planes(48, 32, vec3(0.0f), vec3(0.0f), 0.0f, 0.0f, 7, 4);
  Image color = constant_image(t.color.width, t.color.height, 3, 0.37f);
  for (const NamedFilter& f : kFilters) {
    Image out = f.run(color, t.depth, t.normal);
    EXPECT_LE(max_abs_difference(out, color), 1e-6 * 0.37) << f.name;
  }
  // With history: SVGF's variance from the temporal moments (zero), the luminance weight at its limit.
  Image moments = single_frame_moments(color);
  Image history = constant_image(color.width, color.height, 1, 10.0f);
  SvgfSpatialResult r = svgf_spatial(color, moments, history, t.depth, t.normal, SvgfParams{});
  EXPECT_LE(max_abs_difference(r.filtered, color), 1e-6 * 0.37);
  EXPECT_LE(max_abs_difference(r.level1, color), 1e-6 * 0.37);
}

TEST(Filters, LetNothingBleedAcrossADepthEdge) {
  // Two planes, one of them noisy, the other constant: a filter leaves a constant region as it is
  // unless it takes taps from across the edge, so every pixel of the constant side keeps its value
  // to 1% of its brightest channel. Two pairs of colours: ten times brighter (a leak of 0.1% of
  // weight shows), and red beside blue of the same luminance (SVGF's luminance weight cannot tell
  // them apart: only depth and normal stop it).
  const std::pair<vec3, vec3> pairs[] = {{vec3(0.05f, 0.04f, 0.03f), vec3(0.5f, 0.4f, 0.3f)},
                                         {vec3(0.3f, 0.05f, 0.05f), vec3(0.05f, 0.05f, 0.7871f)}};
  for (auto [left, right] : pairs)
    for (bool noisy_left : {false, true}) {
      test::TwoPlanes t = two_planes(64, 40, left, right, noisy_left ? 0.5f : 0.0f, noisy_left ? 0.0f : 0.5f);
      const int x0 = noisy_left ? t.edge_x : 0, x1 = noisy_left ? t.color.width : t.edge_x;
      const vec3 expected = noisy_left ? right : left;
      for (const NamedFilter& f : kFilters) {
        Image out = f.run(t.color, t.depth, t.normal);
        double worst = 0.0;
        for (int y = 0; y < out.height; ++y)
          for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(out.at(x, y, c) - expected[c])));
        EXPECT_LT(worst / max_component(expected), 0.01)
            << f.name << ", constant side " << (noisy_left ? "right " : "left ") << right.z;
      }
    }
}

TEST(Filters, FilterSomething) {
  // The edge test above passes for a filter that does nothing; this one does not: noise within a
  // plane drops (by more than half in standard deviation for the denoisers).
  test::TwoPlanes t = two_planes(64, 40, vec3(0.3f), vec3(0.3f), 0.5f, 0.5f);
  auto deviation = [](const Image& image, int x0, int x1) {
    double m = band_mean(image, x0, x1), s = 0.0;
    size_t n = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = x0; x < x1; ++x, ++n) s += (image.at(x, y, 0) - m) * (image.at(x, y, 0) - m);
    return std::sqrt(s / double(n));
  };
  const double noisy = deviation(t.color, 4, 28);
  EXPECT_LT(deviation(run_atrous(t.color, t.depth, t.normal), 4, 28), 0.5 * noisy);
  EXPECT_LT(deviation(run_svgf(t.color, t.depth, t.normal), 4, 28), 0.5 * noisy);
  // Upsampling interpolates: between texels the values are blends, so the noise drops a little.
  EXPECT_LT(deviation(run_upsample(t.color, t.depth, t.normal), 4, 28), 0.95 * noisy);
}

TEST(Filters, StayFiniteOnDegenerateInputs) {
  // Black albedo: demodulation neither divides by zero nor loses the light on the way back.
  test::TwoPlanes t = two_planes(16, 12, vec3(0.2f), vec3(0.7f), 0.5f, 0.5f, 3, 2);
  Image black(t.color.width, t.color.height, 3);
  Image light = demodulate(t.color, black);
  EXPECT_TRUE(all_finite(light));
  EXPECT_LE(max_abs_difference(remodulate(light, black), t.color), 1e-6);
  for (const NamedFilter& f : kFilters) EXPECT_TRUE(all_finite(f.run(light, t.depth, t.normal))) << f.name;

  // Zero variance with a long history: the luminance weight's tolerance is zero.
  Image zero_moments(t.color.width, t.color.height, 2);
  Image history = constant_image(t.color.width, t.color.height, 1, 8.0f);
  SvgfSpatialResult r = svgf_spatial(t.color, zero_moments, history, t.depth, t.normal, SvgfParams{});
  EXPECT_TRUE(all_finite(r.filtered) && all_finite(r.level1) && all_finite(r.variance));

  // Nothing hit anywhere: every filter passes the image through.
  Image sky_depth(t.color.width, t.color.height, 1), sky_normal(t.color.width, t.color.height, 3);
  for (const NamedFilter& f : kFilters) {
    if (std::string(f.name) == "upsample") continue;  // its input is half resolution: checked below
    EXPECT_EQ(f.run(t.color, sky_depth, sky_normal).data, t.color.data) << f.name;
  }
  Image low_sky = constant_image(8, 6, 3, 0.25f);
  Image up = joint_bilateral_upsample(low_sky, Image(8, 6, 1), Image(8, 6, 3), sky_depth, sky_normal, UpsampleParams{});
  EXPECT_LE(max_abs_difference(up, constant_image(16, 12, 3, 0.25f)), 1e-7);

  // 1x1, 1xN and Nx1 images: finite, and constant stays constant.
  for (auto [w, h] : {std::pair{1, 1}, std::pair{1, 7}, std::pair{7, 1}, std::pair{2, 1}}) {
    test::TwoPlanes s = two_planes(w, h, vec3(0.4f), vec3(0.9f), 0.5f, 0.5f);
    Image flat = constant_image(w, h, 3, 0.6f);
    for (const NamedFilter& f : kFilters) {
      EXPECT_TRUE(all_finite(f.run(s.color, s.depth, s.normal))) << f.name << " " << w << "x" << h;
      EXPECT_LE(max_abs_difference(f.run(flat, s.depth, s.normal), flat), 1e-6) << f.name << " " << w << "x" << h;
    }
  }
}

TEST(Filters, GiveTheSameBitsWhateverTheThreadCount) {
  test::TwoPlanes t = two_planes(96, 64, vec3(0.2f), vec3(0.7f), 0.5f, 0.5f, 11, 3);
  std::vector<Image> outputs[2];
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    for (const NamedFilter& f : kFilters) outputs[threads - 1].push_back(f.run(t.color, t.depth, t.normal));
  }
  for (size_t i = 0; i < outputs[0].size(); ++i) EXPECT_EQ(outputs[0][i].data, outputs[1][i].data) << kFilters[i].name;
}

TEST(Filters, RejectMismatchedInputsAndImpossibleParameters) {
  test::TwoPlanes t = two_planes(8, 8, vec3(0.2f), vec3(0.7f), 0.0f, 0.0f);
  EXPECT_THROW(atrous_filter(t.color, Image(8, 7, 1), t.normal, AtrousParams{}), Error);
  EXPECT_THROW(atrous_filter(t.color, t.depth, Image(8, 8, 1), AtrousParams{}), Error);
  AtrousParams bad_atrous;
  bad_atrous.sigma_color = 0.0f;
  EXPECT_THROW(atrous_filter(t.color, t.depth, t.normal, bad_atrous), Error);
  EXPECT_THROW(svgf_spatial(t.color, Image(8, 8, 1), Image(8, 8, 1), t.depth, t.normal, SvgfParams{}), Error);
  SvgfParams bad_svgf;
  bad_svgf.levels = -1;
  EXPECT_THROW(svgf_spatial(t.color, Image(8, 8, 2), Image(8, 8, 1), t.depth, t.normal, bad_svgf), Error);
  // A "low-resolution" image larger than the image it is upsampled to; a G-buffer of another size.
  EXPECT_THROW(joint_bilateral_upsample(Image(9, 4), Image(9, 4, 1), Image(9, 4), t.depth, t.normal, UpsampleParams{}),
               Error);
  EXPECT_THROW(joint_bilateral_upsample(Image(3, 4), Image(4, 4, 1), Image(3, 4), t.depth, t.normal, UpsampleParams{}),
               Error);
}

TEST(Filters, UpsamplingFallsBackToTheTexelOfNearestDepth) {
  // A full-resolution pixel whose four texels all lie on another surface (thin geometry the
  // half-resolution G-buffer missed) takes the nearest-depth texel's value, not black.
  Image depth = constant_image(4, 4, 1, 1.0f), normal(4, 4, 3);
  for (int i = 0; i < 16; ++i) normal.data[3 * i + 2] = 1.0f;
  Image low_depth = constant_image(2, 2, 1, 5.0f), low_normal = point_downsample(normal, 2);
  low_depth.at(1, 1, 0) = 3.0f;
  Image low = constant_image(2, 2, 3, 0.1f);
  low.set_rgb(1, 1, vec3(0.8f));
  Image up = joint_bilateral_upsample(low, low_depth, low_normal, depth, normal, UpsampleParams{});
  // Pixel (0, 0)'s four texels are all texel (0, 0) (clamped at the border); from (1, 1) on, texel
  // (1, 1) is among them and nearest in depth.
  EXPECT_FLOAT_EQ(up.at(0, 0, 0), 0.1f);
  for (int y = 1; y < 4; ++y)
    for (int x = 1; x < 4; ++x) EXPECT_FLOAT_EQ(up.at(x, y, 0), 0.8f) << x << "," << y;
}

}  // namespace
}  // namespace sst
