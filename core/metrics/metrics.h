// Image metrics of a test image against a reference, each defined beside its field below.
#pragma once
#include <cstddef>
#include <nlohmann/json_fwd.hpp>

#include "core/image/image.h"
#include "core/math/math.h"
#include "core/metrics/error_map.h"
#include "core/metrics/ssim.h"

namespace sst {

// Error metrics are over all pixels and channels of the linear (HDR) values; ssim is over the
// display images. Non-finite values are never skipped: skipping would reward a method for
// producing NaN where it is hard. They are counted and take part as 0 (black).
struct ImageMetrics {
  int width = 0;
  int height = 0;
  double rmse = 0.0;     // sqrt(mean((t-r)^2))
  double rel_mse = 0.0;  // mean((t-r)^2 / (r^2 + 0.01)): the 0.01 keeps dark pixels from dominating
  // 10 log10(1 / mse) with peak 1: linear HDR has no natural peak, and 1 is display white at
  // exposure 0. +inf when the images are equal (null in JSON).
  double psnr = 0.0;
  // Mean SSIM of the display images, averaged over channels, exactly as scikit-image computes it
  // (see ssim.h). NaN (null in JSON) when the image is smaller than the 11x11 window.
  double ssim = 0.0;
  double mae = 0.0;                // mean |t-r|
  dvec3 mean_test{0.0};            // mean linear RGB of the test image
  dvec3 mean_reference{0.0};       // mean linear RGB of the reference
  size_t nonfinite_test = 0;       // test pixels with a NaN/Inf channel (a defect of the method)
  size_t nonfinite_reference = 0;  // same for the reference (a defect of the reference)
};

// inputs_are_display: both images hold display values (as stored in a PNG); their linear values
// are srgb_decode of them and SSIM uses them as they are. Otherwise both are linear and SSIM uses
// to_display(x) at exposure 0. Throws sst::Error naming both sizes when they differ.
ImageMetrics compare_images(const Image& test, const Image& reference, bool inputs_are_display = false);

// Every field, snake_case; mean_* as [r, g, b]; non-finite numbers as null.
nlohmann::json to_json(const ImageMetrics& metrics);

// The errors over the pixels where `mask` is 0 in its RGB (e.g. the pixels that no directly
// visible emitter touches, from a render of the emitters alone): rmse, rel_mse and mae as
// ImageMetrics defines them, over those pixels' channels. Non-finite values count as 0. Throws
// sst::Error when the three sizes differ.
struct MaskedErrors {
  size_t pixels = 0;  // pixels where the mask is 0
  double rmse = 0.0, rel_mse = 0.0, mae = 0.0;
};
MaskedErrors masked_errors(const Image& test, const Image& reference, const Image& mask);

// Flicker of a sequence between two consecutive frames: the mean squared difference between the
// test's frame-to-frame change and the reference's, over all pixels and channels,
//   mean(((t1 - t0) - (r1 - r0))^2),
// so that motion the reference shows is no flicker, and noise that changes from frame to frame is.
// Sequences report the square root of its mean over all consecutive pairs (docs/sst-eval.md).
// Non-finite values count as 0, as in compare_images. Throws sst::Error when sizes differ.
double flicker_mse(const Image& test0, const Image& test1, const Image& reference0, const Image& reference1);

}  // namespace sst
