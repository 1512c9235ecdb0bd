// One pass of the edge-avoiding a-trous wavelet filter (Dammertz et al. 2010) at one pixel
// (shared C++/GLSL source; filters.h runs the passes). Hooks: FILTER_COLOR, FILTER_DEPTH,
// FILTER_NORMAL (filter_kernel_common.h).
#ifndef SST_CORE_FILTER_ATROUS_KERNEL_H
#define SST_CORE_FILTER_ATROUS_KERNEL_H
#include "core/filter/filter_kernel_common.h"

SST_BEGIN

// The 5x5 B3-spline taps 2^level apart, each weighted by how alike its colour, normal and depth are
// to the pixel's. Depth enters relative to the pixel's depth (Dammertz compare world positions):
// a scene in millimetres filters as one in metres.
SST_FUNC vec3 atrous_pixel(FILTER_CTX_PARAM SST_IN(AtrousPush) p, int x, int y) {
  int width = int(p.width);
  int height = int(p.height);
  int i = y * width + x;
  vec3 c = FILTER_COLOR(i);
  float z = FILTER_DEPTH(i);
  if (!filter_has_surface(z)) return c;
  vec3 n = FILTER_NORMAL(i);
  int step = int(p.step);
  vec3 sum = vec3(0.0f);
  float weight_sum = 0.0f;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      int j = filter_surface_tap(FILTER_CTX x + dx * step, y + dy * step, width, height);
      if (j < 0) continue;
      float zq = FILTER_DEPTH(j);
      vec3 cq = FILTER_COLOR(j);
      vec3 dc = c - cq;
      vec3 dn = n - FILTER_NORMAL(j);
      float dz = (z - zq) / z;
      float e = dot3(dc, dc) * p.inv_color + dot3(dn, dn) * p.inv_normal + dz * dz * p.inv_depth;
      float w = exp(-e) * filter_b3(dx) * filter_b3(dy);
      sum += w * cq;
      weight_sum += w;
    }
  }
  // The centre tap weighs exp(0) 9/64, so the sum is positive unless the colour is not finite.
  return weight_sum > 0.0f ? sum / weight_sum : c;
}

SST_END

#endif  // SST_CORE_FILTER_ATROUS_KERNEL_H
