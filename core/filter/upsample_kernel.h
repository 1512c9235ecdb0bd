// Joint bilateral upsampling at one full-resolution pixel (the hybrid thesis, ch. 6 and 7.4;
// shared C++/GLSL source; filters.h runs it). Hooks: FILTER_COLOR (the low-resolution image),
// FILTER_LOW_DEPTH, FILTER_LOW_NORMAL, FILTER_DEPTH, FILTER_NORMAL (filter_kernel_common.h).
#ifndef SST_CORE_FILTER_UPSAMPLE_KERNEL_H
#define SST_CORE_FILTER_UPSAMPLE_KERNEL_H
#include "core/filter/filter_kernel_common.h"
#include "core/math/geometric_similarity.h"

SST_BEGIN

// The bilinear blend of the four low-resolution texels around the pixel (clamped at the border),
// keeping only those whose surface is geometrically similar to the pixel's;
// a pixel without a surface blends texels without one. With none similar (thin geometry, a
// silhouette between texels) the pixel takes the texel of nearest depth: a real neighbouring value,
// never a hole.
SST_FUNC vec3 upsample_pixel(FILTER_CTX_PARAM SST_IN(UpsamplePush) p, int x, int y) {
  int i = y * int(p.width) + x;
  float z = FILTER_DEPTH(i);
  vec3 n = FILTER_NORMAL(i);
  bool surface = filter_has_surface(z);
  // Texel centres in pixel units: the low-resolution image spans the same view, whatever rounding
  // made its size.
  SST_PRECISE float fx = (float(x) + 0.5f) * (float(p.low_width) / float(p.width)) - 0.5f;
  SST_PRECISE float fy = (float(y) + 0.5f) * (float(p.low_height) / float(p.height)) - 0.5f;
  int bx = int(floor(fx));
  int by = int(floor(fy));
  float tx = fx - float(bx);
  float ty = fy - float(by);
  vec3 sum = vec3(0.0f);
  float weight_sum = 0.0f;
  int nearest = 0;
  float nearest_difference = 0.0f;
  for (int c = 0; c < 4; ++c) {
    int cx = clamp(bx + (c & 1), 0, int(p.low_width) - 1);
    int cy = clamp(by + (c >> 1), 0, int(p.low_height) - 1);
    int j = cy * int(p.low_width) + cx;
    float zq = FILTER_LOW_DEPTH(j);
    bool similar = surface ? filter_has_surface(zq) &&
                                 geometrically_similar(n, FILTER_LOW_NORMAL(j), abs(z - zq), p.n_min, p.d_max * z)
                           : !filter_has_surface(zq);
    float wx = (c & 1) != 0 ? tx : 1.0f - tx;
    float wy = (c >> 1) != 0 ? ty : 1.0f - ty;
    float w = similar ? wx * wy : 0.0f;
    sum += w * FILTER_COLOR(j);
    weight_sum += w;
    float difference = abs(z - zq);
    if (c == 0 || difference < nearest_difference) {
      nearest = j;
      nearest_difference = difference;
    }
  }
  return weight_sum > 0.0f ? sum / weight_sum : FILTER_COLOR(nearest);
}

SST_END

#endif  // SST_CORE_FILTER_UPSAMPLE_KERNEL_H
