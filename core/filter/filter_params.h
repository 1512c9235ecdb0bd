// The parameters of the G-buffer-guided filters, one struct each (core/util/params.h's pattern),
// with the papers' defaults, and the push constants both backends run them with.
#pragma once
#include "core/filter/filter_layout.h"

namespace sst {

// Edge-avoiding a-trous wavelet filter (Dammertz et al. 2010): `levels` passes of a 5x5 B3-spline
// kernel with holes 2^level, each tap weighted by exp(-|dc|^2 / (sigma_color^2 2^-level)
// - |dn|^2 / (sigma_normal^2 4^level) - (dz / z)^2 / sigma_depth^2).
struct AtrousParams {
  int levels = 5;
  float sigma_color = 1.0f;
  float sigma_normal = 0.3f;
  float sigma_depth = 0.05f;

  template <class V>
  void visit(V&& v) {
    v("atrous_levels", levels, "a-trous passes; pass i spaces its 5x5 taps 2^i pixels apart (0: no filtering)");
    v("atrous_sigma_color", sigma_color,
      "colour edge-stopping: RGB distance at which a tap's weight falls to 1/e at the first pass (halved in "
      "variance each pass, as Dammertz et al.)");
    v("atrous_sigma_normal", sigma_normal, "normal edge-stopping: distance between unit normals at which a tap's weight falls to 1/e");
    v("atrous_sigma_depth", sigma_depth,
      "depth edge-stopping: depth difference, as a fraction of the pixel's depth, at which a tap's weight falls to 1/e");
  }
};

// SVGF's spatial stages (Schied et al. 2017): the luminance variance from the temporal moments (or
// a 7x7 bilateral estimate while the history is short), then `levels` a-trous passes with weights
// exp(-|dz| / (sigma_z |grad z . d| + eps)) max(0, n.n')^sigma_n exp(-|dl| / (sigma_l sqrt(g3x3(var)) + eps)).
struct SvgfParams {
  int levels = 5;
  float sigma_z = 1.0f;
  float sigma_n = 128.0f;
  float sigma_l = 4.0f;
  int min_history = 4;

  template <class V>
  void visit(V&& v) {
    v("svgf_levels", levels, "a-trous passes; pass i spaces its 5x5 taps 2^i pixels apart (0: no filtering)");
    v("svgf_sigma_z", sigma_z, "depth edge-stopping: tolerance in units of the depth change the local depth gradient predicts");
    v("svgf_sigma_n", sigma_n, "normal edge-stopping: exponent of the cosine between the normals");
    v("svgf_sigma_l", sigma_l, "luminance edge-stopping: tolerance in standard deviations of the pixel's luminance");
    v("svgf_min_history", min_history,
      "frames of history from which the temporal moments give the variance; below it a 7x7 bilateral spatial "
      "estimate of the moments does");
  }
};

// Joint bilateral upsampling (the hybrid thesis, ch. 6): each full-resolution pixel blends its four
// nearest low-resolution texels bilinearly, keeping only those geometrically similar to it
// (core/math/geometric_similarity.h, with the depth difference as the distance).
struct UpsampleParams {
  float n_min = 0.9f;
  float d_max = 0.05f;

  template <class V>
  void visit(V&& v) {
    v("upsample_n_min", n_min, "a texel is used only if the cosine between its normal and the pixel's is > n_min");
    v("upsample_d_max", d_max,
      "a texel is used only if its depth differs from the pixel's by less than d_max x the pixel's depth (the "
      "thesis's d_max, made relative so that it holds at any scene scale); with no such texel the pixel takes "
      "the texel of nearest depth");
  }
};

// sst::Error naming the bad parameter and its value.
void validate(const AtrousParams& params);
void validate(const SvgfParams& params);
void validate(const UpsampleParams& params);

// The push constants of a-trous level `level` and of SVGF dispatch `pass` at `level`.
glsl::AtrousPush atrous_push(const AtrousParams& params, int width, int height, int level);
glsl::SvgfPush svgf_push(const SvgfParams& params, int width, int height, uint32_t pass, int level);
glsl::UpsamplePush upsample_push(const UpsampleParams& params, int width, int height, int low_width, int low_height);

}  // namespace sst
