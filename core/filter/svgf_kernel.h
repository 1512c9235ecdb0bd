// SVGF's spatial stages at one pixel (Schied et al. 2017; shared C++/GLSL source; filters.h runs
// them): the luminance variance, then one edge-avoiding a-trous pass guided by depth, normal and
// that variance. Hooks: FILTER_COLOR, FILTER_VARIANCE, FILTER_MOMENTS, FILTER_HISTORY,
// FILTER_DEPTH, FILTER_NORMAL (filter_kernel_common.h).
#ifndef SST_CORE_FILTER_SVGF_KERNEL_H
#define SST_CORE_FILTER_SVGF_KERNEL_H
#include "core/filter/filter_kernel_common.h"

SST_BEGIN

SST_FUNC float svgf_depth_at(FILTER_CTX_PARAM int x, int y, int width, int height) {
  return filter_inside(x, y, width, height) ? FILTER_DEPTH(y * width + x) : 0.0f;
}

// The depth's change per pixel along one axis, from the neighbours at -1 (zm) and +1 (zp): the
// smaller one-sided difference, so that a pixel on a depth edge takes its own surface's slope. A
// central difference would take the jump, and the depth weight, which tolerates what the slope
// predicts, would then let taps across the edge through.
SST_FUNC float svgf_slope(float z, float zm, float zp) {
  bool has_m = filter_has_surface(zm);
  bool has_p = filter_has_surface(zp);
  float dm = z - zm;
  float dp = zp - z;
  if (has_m && has_p) return abs(dm) < abs(dp) ? dm : dp;
  return has_m ? dm : (has_p ? dp : 0.0f);
}

SST_FUNC vec2 svgf_depth_gradient(FILTER_CTX_PARAM int x, int y, int width, int height, float z) {
  return vec2(svgf_slope(z, svgf_depth_at(FILTER_CTX x - 1, y, width, height),
                         svgf_depth_at(FILTER_CTX x + 1, y, width, height)),
              svgf_slope(z, svgf_depth_at(FILTER_CTX x, y - 1, width, height),
                         svgf_depth_at(FILTER_CTX x, y + 1, width, height)));
}

// -log of the depth weight of a tap `offset` pixels away: the depth difference in units of what the
// gradient predicts. The epsilon, 1% of the depth, keeps a plane facing the camera (zero gradient)
// filterable and is scale-free.
SST_FUNC float svgf_depth_exponent(float z, float zq, vec2 gradient, vec2 offset, float sigma_z) {
  float predicted = abs(gradient.x * offset.x + gradient.y * offset.y);
  return abs(z - zq) / (sigma_z * predicted + 0.01f * z);
}

SST_FUNC float svgf_normal_weight(vec3 n, vec3 nq, float sigma_n) { return pow(max(dot3(n, nq), 0.0f), sigma_n); }

// The variance of the pixel's luminance: from its temporal moments once `min_history` frames back
// them, before that from the moments of the 7x7 neighbourhood weighted by depth and normal alone.
// 0 where nothing was hit.
SST_FUNC float svgf_variance_pixel(FILTER_CTX_PARAM SST_IN(SvgfPush) p, int x, int y) {
  int width = int(p.width);
  int height = int(p.height);
  int i = y * width + x;
  float z = FILTER_DEPTH(i);
  if (!filter_has_surface(z)) return 0.0f;
  vec2 m = FILTER_MOMENTS(i);
  if (FILTER_HISTORY(i) < p.min_history) {
    vec3 n = FILTER_NORMAL(i);
    vec2 gradient = svgf_depth_gradient(FILTER_CTX x, y, width, height, z);
    vec2 sum = vec2(0.0f);
    float weight_sum = 0.0f;
    for (int dy = -3; dy <= 3; ++dy) {
      for (int dx = -3; dx <= 3; ++dx) {
        int j = filter_surface_tap(FILTER_CTX x + dx, y + dy, width, height);
        if (j < 0) continue;
        float e = svgf_depth_exponent(z, FILTER_DEPTH(j), gradient, vec2(float(dx), float(dy)), p.sigma_z);
        float w = exp(-e) * svgf_normal_weight(n, FILTER_NORMAL(j), p.sigma_n);
        sum += w * FILTER_MOMENTS(j);
        weight_sum += w;
      }
    }
    // The centre weighs 1 unless its normal is degenerate; then its own moments stand.
    if (weight_sum > 0.0f) m = sum / weight_sum;
  }
  return max(m.y - m.x * m.x, 0.0f);
}

// One a-trous pass with SVGF's weights at one pixel: the filtered illumination (x, y, z) and its
// variance (w), filtered with the squared weights. Pixels without a surface pass through.
SST_FUNC vec4 svgf_atrous_pixel(FILTER_CTX_PARAM SST_IN(SvgfPush) p, int x, int y) {
  int width = int(p.width);
  int height = int(p.height);
  int i = y * width + x;
  vec3 c = FILTER_COLOR(i);
  float variance = FILTER_VARIANCE(i);
  float z = FILTER_DEPTH(i);
  if (!filter_has_surface(z)) return vec4(c.x, c.y, c.z, variance);
  vec3 n = FILTER_NORMAL(i);
  vec2 gradient = svgf_depth_gradient(FILTER_CTX x, y, width, height, z);
  // The luminance tolerance from the variance blurred over 3x3 (1 2 1 / 4 per axis) surface pixels:
  // one pixel's variance estimate is itself noisy.
  float blurred = 0.0f;
  float blur_weight = 0.0f;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      int j = filter_surface_tap(FILTER_CTX x + dx, y + dy, width, height);
      if (j < 0) continue;
      float k = (dx == 0 ? 0.5f : 0.25f) * (dy == 0 ? 0.5f : 0.25f);
      blurred += k * FILTER_VARIANCE(j);
      blur_weight += k;
    }
  }
  // Without variance only equal luminances pass (the epsilon keeps 0 / 0 out).
  float phi_l = p.sigma_l * sqrt(max(blurred / blur_weight, 0.0f)) + 1e-10f;
  float l = luminance(c);
  int step = int(p.step);
  vec3 sum = vec3(0.0f);
  float variance_sum = 0.0f;
  float weight_sum = 0.0f;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      int j = filter_surface_tap(FILTER_CTX x + dx * step, y + dy * step, width, height);
      if (j < 0) continue;
      vec3 cq = FILTER_COLOR(j);
      float e = svgf_depth_exponent(z, FILTER_DEPTH(j), gradient, vec2(float(dx * step), float(dy * step)), p.sigma_z) +
                abs(l - luminance(cq)) / phi_l;
      float w = exp(-e) * svgf_normal_weight(n, FILTER_NORMAL(j), p.sigma_n) * filter_b3(dx) * filter_b3(dy);
      sum += w * cq;
      variance_sum += w * w * FILTER_VARIANCE(j);
      weight_sum += w;
    }
  }
  if (!(weight_sum > 0.0f)) return vec4(c.x, c.y, c.z, variance);
  vec3 filtered = sum / weight_sum;
  return vec4(filtered.x, filtered.y, filtered.z, variance_sum / (weight_sum * weight_sum));
}

SST_END

#endif  // SST_CORE_FILTER_SVGF_KERNEL_H
