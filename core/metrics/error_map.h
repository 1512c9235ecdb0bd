// Per-pixel error images: what the report shows and what statistical tests consume.
#pragma once
#include "core/image/image.h"

namespace sst {

// 1 channel: mean over channels of |t-r| divided by (mean over channels of |r|) + 0.01, the same
// dark-pixel guard as rel_mse. Non-finite values count as 0.
Image relative_error_image(const Image& test, const Image& reference);
// Per channel (t-r)^2 on linear values; with a per-pixel variance image it gives z-scores.
Image squared_error_image(const Image& test, const Image& reference);
// Relative error mapped through matplotlib's inferno (0 -> black, >= max_error -> pale yellow),
// returned as *linear* RGB so that write_image(".png") reproduces the colormap's sRGB colours.
Image error_heatmap(const Image& test, const Image& reference, float max_error = 1.0f);
// inferno at t in [0,1] (clamped), as display (sRGB-encoded) RGB.
vec3 inferno(float t);
// A 1-channel image of values through inferno (0 -> black, >= max_value -> pale yellow), as linear
// RGB: error_heatmap's colours for any per-pixel error, e.g. a FLIP map (core/metrics/flip.h).
Image inferno_image(const Image& values, float max_value = 1.0f);

}  // namespace sst
