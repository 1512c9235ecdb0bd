// A screen probe's 64 texels summed over what reaches them (S2, S6, S14 and the side cache): one
// invocation owns the sums, so their order is fixed on both backends.
#ifndef SST_CORE_GI10_GI10_PROBE_TEXELS_H
#define SST_CORE_GI10_GI10_PROBE_TEXELS_H
#include "core/gi10/gi10_buffers.h"

SST_BEGIN

struct GiTexelSums {
  vec4 sum[64];  // radiance, hit distance
  float count[64];
};

SST_FUNC void gi_sums_clear(SST_INOUT(GiTexelSums) a) {
  for (uint c = 0u; c < 64u; ++c) {
    a.sum[c] = vec4(0.0f);
    a.count[c] = 0.0f;
  }
}

// Adds the texel of another probe (at xq, frame fq) seen from probe x, n (frame fx): its radiance
// arrives from the point it hit (parallax), or, for a miss, from its direction. False when it lies
// outside the hemisphere of n.
SST_FUNC bool gi_sums_add_reprojected(SST_INOUT(GiTexelSums) a, vec3 x, vec3 n, SST_IN(GiFrame) fx, vec3 xq,
                                      SST_IN(GiFrame) fq, uint c, vec4 value, bool strict_hemisphere) {
  vec3 wq = gi_texel_direction(fq, c);
  vec3 w;
  float d;
  if (gi_is_miss(value.w)) {
    w = wq;
    d = kGiMissDistance;
  } else {
    SST_PRECISE vec3 h = xq + wq * value.w;
    vec3 hx = h - x;
    d = length3(hx);
    if (!(d > 0.0f)) return false;
    w = hx / d;
  }
  float cos_n = dot3(n, w);
  if (strict_hemisphere ? !(cos_n > 0.0f) : !(cos_n >= 0.0f)) return false;
  uint k = gi_texel_of(fx, w);
  a.sum[k] += vec4(value.x, value.y, value.z, d);
  a.count[k] += 1.0f;
  return true;
}

// The radiance given to texels that received nothing: the mean of the texels rays reached, or, as
// Capsaicin computes it, that mean spread over the empty texels (divided by their number). Guiding sends no ray to the texels it predicts dark, so the mean brightens them and the
// spread darkens them: measured in configs/gi10-static-one-bounce.json.
SST_FUNC vec3 gi_backup(SST_IN(GiTexelSums) a, bool mean) {
  vec3 sum = vec3(0.0f);
  vec3 texel_means = vec3(0.0f);
  float populated = 0.0f;
  for (uint c = 0u; c < 64u; ++c) {
    sum += gi_rgb(a.sum[c]);
    if (a.count[c] > 0.0f) {
      texel_means += gi_rgb(a.sum[c]) / a.count[c];
      populated += 1.0f;
    }
  }
  if (!mean) return sum / max(populated, 1.0f) / max(64.0f - populated, 1.0f);
  return populated > 0.0f ? texel_means / populated : vec3(0.0f);
}

SST_FUNC vec4 gi_sums_texel(SST_IN(GiTexelSums) a, uint c, vec3 backup) {
  if (a.count[c] > 0.0f) return a.sum[c] / a.count[c];
  return gi_vec4(backup, kGiMissDistance);
}

SST_END

#endif  // SST_CORE_GI10_GI10_PROBE_TEXELS_H
