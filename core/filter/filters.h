// Image filters guided by the G-buffer, on the CPU: the edge-avoiding a-trous filter (Dammertz et
// al. 2010), SVGF's spatial stages (Schied et al. 2017) and joint bilateral upsampling (the hybrid
// thesis, ch. 6). The per-pixel kernels are shared with the Vulkan backend (gpu/filter_pass.h);
// these drivers run them over the image with oneTBB, each pixel written by one task from images no
// task writes, so the output is the same whatever the thread count.
//
// The G-buffer images are core/render/frame.h's AOVs: depth (1 channel, distance from the camera, 0
// where nothing was hit: such pixels keep their values and are never taps) and normal (RGB, world
// space). Every image of a call has the same size except the upsampler's low-resolution inputs.
// Mismatched sizes or channel counts and impossible parameters are an sst::Error naming them.
#pragma once
#include "core/filter/filter_params.h"
#include "core/image/image.h"

namespace sst {

// `levels` a-trous passes over `color` (RGB).
Image atrous_filter(const Image& color, const Image& depth, const Image& normal, const AtrousParams& params);

struct SvgfSpatialResult {
  Image filtered;  // RGB: the illumination after every a-trous level
  Image level1;    // RGB: after the first level (SVGF feeds it into the colour history); the input for 0 levels
  Image variance;  // 1 channel: the luminance variance estimated before filtering (0 without a surface)
};
// `illumination`: albedo-demodulated light (RGB); `moments`: E[l], E[l^2] of its luminance over time
// (2 channels); `history_length`: the frames behind them (1 channel).
SvgfSpatialResult svgf_spatial(const Image& illumination, const Image& moments, const Image& history_length,
                               const Image& depth, const Image& normal, const SvgfParams& params);

// `low` (RGB) and its G-buffer `low_depth`, `low_normal`, rendered at a lower resolution of the same
// view (any size up to that of `depth` and `normal`), to the full resolution.
Image joint_bilateral_upsample(const Image& low, const Image& low_depth, const Image& low_normal, const Image& depth,
                               const Image& normal, const UpsampleParams& params);

// light / albedo and its inverse, per channel, with the albedo clamped to at least 0.01
// (filter_albedo_divisor): what the filters and temporal reuse smooth, and how the result becomes
// light again; finite for black albedo.
Image demodulate(const Image& light, const Image& albedo);
Image remodulate(const Image& illumination, const Image& albedo);
// Their per-pixel divisor, for passes that demodulate as they go.
vec3 albedo_divisor(vec3 albedo);

// The checks every backend runs before filtering: sst::Error naming the first input whose size or
// channel count does not fit, or the impossible parameter.
void check_atrous_inputs(const Image& color, const Image& depth, const Image& normal, const AtrousParams& params);
void check_svgf_inputs(const Image& illumination, const Image& moments, const Image& history_length,
                       const Image& depth, const Image& normal, const SvgfParams& params);
void check_upsample_inputs(const Image& low, const Image& low_depth, const Image& low_normal, const Image& depth,
                           const Image& normal, const UpsampleParams& params);

}  // namespace sst
