// Temporal reuse on the CPU: a frame's AOVs and motion turned into the per-pixel inputs of
// core/temporal/temporal_accumulate.h, the accumulation itself, and the history that carries it
// from frame to frame. The Vulkan side (gpu/temporal_pass.h) runs the same kernel.
#pragma once
#include <vector>

#include "core/image/image.h"
#include "core/temporal/temporal_layout.h"

namespace sst {

struct TemporalParams {
  int history_cap = 20;  // Falcor's SVGF alpha 0.05
  float depth_tolerance = 0.1f;
  float normal_cos = 0.9f;

  template <class V>
  void visit(V&& v) {
    v("history_cap", history_cap,
      "temporal reuse: the most frames a pixel's average holds (alpha = 1 / min(frames, cap)); 1 keeps no history");
    v("depth_tolerance", depth_tolerance,
      "temporal reuse: history is kept where its depth is within this fraction of the reprojected point's distance");
    v("normal_cos", normal_cos, "temporal reuse: ... and where its normal is within this cosine of the current one, widened by how much "
      "the normal turns from one pixel to the next");
  }
};

void validate(const TemporalParams& params);

// Per pixel: direct and indirect radiance, the mean first-hit albedo of the same samples
// (FrameOutput::albedo), the luminance of their ratio (core/filter/filters.h's demodulate), depth,
// normal, motion (2 channels) and the previous frame's distance of the point seen
// (core/render/centre_gbuffer.h).
std::vector<TemporalInput> temporal_inputs(const Image& direct, const Image& indirect, const Image& albedo,
                                           const Image& depth, const Image& normal, const Image& motion,
                                           const Image& previous_depth);

// One frame of accumulation: the new history from the previous one (empty: the first frame).
std::vector<TemporalTexel> temporal_accumulate(const std::vector<TemporalInput>& input,
                                               const std::vector<TemporalTexel>& history, const TemporalPush& push);

TemporalPush temporal_push(const TemporalParams& params, int width, int height);

// The history's averages as images, in one pass: the direct and indirect illumination (averaged
// radiance demodulated by the averaged albedo) and that albedo (RGB), and what SVGF filters the
// indirect light with: the moments of its luminance (2 channels: E[l], E[l^2]) and the frames
// behind them (1 channel).
struct TemporalImages {
  Image direct, indirect, albedo, indirect_moments, frames;
};
TemporalImages temporal_images(const std::vector<TemporalTexel>& history, int width, int height);

// Replaces the history's indirect light by `illumination` remodulated by `albedo` (the history's,
// from temporal_images): SVGF's feedback of its filtered light.
void set_temporal_indirect(std::vector<TemporalTexel>& history, const Image& illumination, const Image& albedo);

}  // namespace sst
