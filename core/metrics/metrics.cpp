#include "core/metrics/metrics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/metrics/same_shape.h"
#include "core/util/error.h"
#include "core/util/json_io.h"

namespace sst {
namespace {

// Linear and display versions of one input, with non-finite values set to 0 and counted.
struct Prepared {
  Image linear;
  Image display;
  size_t nonfinite_pixels = 0;
};

size_t zero_nonfinite(Image& image) {
  size_t pixels = 0;
  for (size_t p = 0; p < image.pixel_count(); ++p) {
    bool bad = false;
    for (int c = 0; c < image.channels; ++c) {
      float& v = image.data[p * image.channels + c];
      if (!std::isfinite(v)) {
        v = 0.0f;
        bad = true;
      }
    }
    pixels += bad;
  }
  return pixels;
}

Prepared prepare(const Image& input, bool is_display) {
  Prepared out;
  Image clean = input;
  out.nonfinite_pixels = zero_nonfinite(clean);
  if (is_display) {
    out.linear = from_display(clean);
    out.display = std::move(clean);
  } else {
    out.display = to_display(clean);
    out.linear = std::move(clean);
  }
  return out;
}

dvec3 mean_rgb(const Image& image) {
  dvec3 sum(0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += dvec3(image.rgb(x, y));
  return image.pixel_count() ? sum / double(image.pixel_count()) : sum;
}

struct ErrorSums {
  double squared = 0.0, relative = 0.0, absolute = 0.0;
  size_t pixels = 0;
};

// Sums per row in parallel, then over rows in order: the same bits whatever the thread count.
// With a mask, only the pixels where its RGB is 0. Inputs hold finite values.
ErrorSums error_sums(const Image& test, const Image& reference, const Image* mask = nullptr) {
  const int channels = test.channels;
  std::vector<ErrorSums> rows(test.height);
  tbb::parallel_for(tbb::blocked_range<int>(0, test.height), [&](const tbb::blocked_range<int>& range) {
    for (int y = range.begin(); y < range.end(); ++y) {
      ErrorSums s;
      for (int x = 0; x < test.width; ++x) {
        if (mask && mask->rgb(x, y) != vec3(0.0f)) continue;
        ++s.pixels;
        for (size_t i = (size_t(y) * test.width + x) * channels, end = i + channels; i < end; ++i) {
          const double t = test.data[i], r = reference.data[i], d = t - r;
          s.squared += d * d;
          s.relative += d * d / (r * r + 0.01);
          s.absolute += std::abs(d);
        }
      }
      rows[y] = s;
    }
  });
  ErrorSums total;
  for (const ErrorSums& s : rows) {
    total.squared += s.squared;
    total.relative += s.relative;
    total.absolute += s.absolute;
    total.pixels += s.pixels;
  }
  return total;
}

void add_error_sums(const Image& test, const Image& reference, ImageMetrics& m) {
  const ErrorSums sums = error_sums(test, reference);
  const double se = sums.squared, rel = sums.relative, ae = sums.absolute;
  const double n = double(test.data.size());
  const double mse = n > 0 ? se / n : 0.0;
  m.rmse = std::sqrt(mse);
  m.rel_mse = n > 0 ? rel / n : 0.0;
  m.mae = n > 0 ? ae / n : 0.0;
  m.psnr = mse > 0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
}

}  // namespace

MaskedErrors masked_errors(const Image& test, const Image& reference, const Image& mask) {
  require_same_shape(test, reference);
  if (mask.width != test.width || mask.height != test.height)
    throw Error("the mask is " + std::to_string(mask.width) + "x" + std::to_string(mask.height) + ", the images " +
                std::to_string(test.width) + "x" + std::to_string(test.height));
  Image t = test, r = reference;
  zero_nonfinite(t);
  zero_nonfinite(r);
  const ErrorSums sums = error_sums(t, r, &mask);
  MaskedErrors e;
  e.pixels = sums.pixels;
  const double n = double(e.pixels) * test.channels;
  if (n > 0) {
    e.rmse = std::sqrt(sums.squared / n);
    e.rel_mse = sums.relative / n;
    e.mae = sums.absolute / n;
  }
  return e;
}

ImageMetrics compare_images(const Image& test, const Image& reference, bool inputs_are_display) {
  require_same_shape(test, reference);
  const Prepared t = prepare(test, inputs_are_display);
  const Prepared r = prepare(reference, inputs_are_display);
  ImageMetrics m;
  m.width = test.width;
  m.height = test.height;
  add_error_sums(t.linear, r.linear, m);
  m.ssim = ssim(t.display, r.display);
  m.mean_test = mean_rgb(t.linear);
  m.mean_reference = mean_rgb(r.linear);
  m.nonfinite_test = t.nonfinite_pixels;
  m.nonfinite_reference = r.nonfinite_pixels;
  return m;
}

nlohmann::json to_json(const ImageMetrics& m) {
  auto rgb = [](dvec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  return {{"width", m.width},
          {"height", m.height},
          {"rmse", number_or_null(m.rmse)},
          {"rel_mse", number_or_null(m.rel_mse)},
          {"psnr", number_or_null(m.psnr)},
          {"ssim", number_or_null(m.ssim)},
          {"mae", number_or_null(m.mae)},
          {"mean_test", rgb(m.mean_test)},
          {"mean_reference", rgb(m.mean_reference)},
          {"nonfinite_test", m.nonfinite_test},
          {"nonfinite_reference", m.nonfinite_reference}};
}

double flicker_mse(const Image& test0, const Image& test1, const Image& reference0, const Image& reference1) {
  for (const Image* i : {&test1, &reference0, &reference1})
    if (i->width != test0.width || i->height != test0.height || i->channels != test0.channels)
      throw Error("flicker: frames of different sizes");
  auto finite = [](float v) { return std::isfinite(v) ? double(v) : 0.0; };
  double sum = 0.0;
  for (size_t i = 0; i < test0.data.size(); ++i) {
    double d = (finite(test1.data[i]) - finite(test0.data[i])) - (finite(reference1.data[i]) - finite(reference0.data[i]));
    sum += d * d;
  }
  return test0.data.empty() ? 0.0 : sum / double(test0.data.size());
}

}  // namespace sst
