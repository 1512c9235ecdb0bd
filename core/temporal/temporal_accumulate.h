// Temporal reuse of one pixel (shared C++/GLSL source): the previous frame's history is read at
// the pixel's motion-vector position with bilinear taps, each tap kept only when it saw the same
// surface (its depth matches the point's distance from the previous camera, its normal the
// current normal), and the current frame is blended in with alpha = 1 / min(history + 1, cap): a
// running mean for the first `cap` frames, then an exponential average, of radiance and albedo
// alike. Moments of the illumination's luminance are accumulated alongside for SVGF's variance
// estimate (Schied et al. 2017, sec. 4.1).
//
// Hooks: TEMPORAL_HISTORY(i) -> TemporalTexel, the previous frame's history of pixel i (row-major);
// TEMPORAL_CTX_PARAM, a leading parameter declaration (with its comma) through which the C++
// binding passes the history (empty in GLSL, where it is a buffer).
#ifndef SST_CORE_TEMPORAL_TEMPORAL_ACCUMULATE_H
#define SST_CORE_TEMPORAL_TEMPORAL_ACCUMULATE_H
#include "core/math/vector_math.h"
#include "core/temporal/temporal_layout.h"

SST_BEGIN

// Whether history texel h saw the surface the current pixel c sees. A pixel whose centre ray
// missed continues the history of misses (the background, reprojected by direction): its samples
// may still hit something small, a lamp's bulb at a silhouette, which without history would
// flash at full strength in the one frame a sample finds it.
SST_FUNC bool temporal_same_surface(SST_IN(TemporalTexel) h, SST_IN(TemporalInput) c, SST_IN(TemporalPush) push) {
  if (!(c.depth > 0.0f)) return !(h.depth > 0.0f);
  if (!(h.depth > 0.0f)) return false;
  SST_PRECISE float depth_error = abs(h.depth - c.previous_depth);
  if (!(depth_error <= push.depth_tolerance * c.previous_depth)) return false;
  // A tap lies within a pixel of the reprojected point, so on a surface whose normal turns fast
  // across pixels (a cup's rim, a chair leg) its normal may differ by as much as a pixel's step
  // without being another surface (Falcor's SVGF scales its normal test by fwidth alike); without
  // that allowance such pixels never keep history, and a single bright sample shows at full
  // strength. The cosine bound alone holds on flat surfaces.
  SST_PRECISE vec3 d = h.normal - c.normal;
  SST_PRECISE float allowed = sqrt(max(2.0f - 2.0f * push.normal_cos, 0.0f)) + c.normal_change;
  return dot3(d, d) <= allowed * allowed;
}

SST_FUNC vec4 temporal_moments(vec2 luminance) {
  SST_PRECISE vec4 m = vec4(luminance.x, luminance.x * luminance.x, luminance.y, luminance.y * luminance.y);
  return m;
}

// The history of pixel (x, y) after adding the current frame's input c.
SST_FUNC TemporalTexel temporal_accumulate_pixel(TEMPORAL_CTX_PARAM int x, int y, SST_IN(TemporalInput) c, SST_IN(TemporalPush) push) {
  vec3 direct = vec3(0.0f, 0.0f, 0.0f);
  vec3 indirect = vec3(0.0f, 0.0f, 0.0f);
  vec3 albedo = vec3(0.0f, 0.0f, 0.0f);
  vec4 moments = vec4(0.0f, 0.0f, 0.0f, 0.0f);
  float frames = 0.0f;
  float weight_sum = 0.0f;
  // A hit needs the previous camera's distance to test the history against (0: not in its view).
  if (!(c.depth > 0.0f) || c.previous_depth > 0.0f) {
    // Pixel centres sit at +0.5: the tap grid starts half a pixel before the reprojected centre.
    SST_PRECISE float fx = float(x) + c.motion.x;
    SST_PRECISE float fy = float(y) + c.motion.y;
    float x0 = floor(fx);
    float y0 = floor(fy);
    SST_PRECISE float tx = fx - x0;
    SST_PRECISE float ty = fy - y0;
    for (int k = 0; k < 4; ++k) {
      int dx = k % 2;
      int dy = k / 2;
      SST_PRECISE float w = (dx == 1 ? tx : 1.0f - tx) * (dy == 1 ? ty : 1.0f - ty);
      int xi = int(x0) + dx;
      int yi = int(y0) + dy;
      if (!(w > 0.0f) || xi < 0 || yi < 0 || xi >= int(push.width) || yi >= int(push.height)) continue;
      TemporalTexel h = TEMPORAL_HISTORY(uint(yi) * push.width + uint(xi));
      if (!temporal_same_surface(h, c, push)) continue;
      SST_PRECISE vec3 wd = h.direct * w;
      SST_PRECISE vec3 wi = h.indirect * w;
      SST_PRECISE vec3 wa = h.albedo * w;
      SST_PRECISE vec4 wm = h.moments * w;
      direct += wd;
      indirect += wi;
      albedo += wa;
      moments += wm;
      frames += h.frames * w;
      weight_sum += w;
    }
  }
  // A history tap of tiny weight would be divided up into a whole frame's worth of trust.
  if (weight_sum > 0.01f) {
    SST_PRECISE float inv = 1.0f / weight_sum;
    direct = direct * inv;
    indirect = indirect * inv;
    albedo = albedo * inv;
    moments = moments * inv;
    frames = frames * inv;
  } else {
    frames = 0.0f;
  }
  float n = min(frames + 1.0f, push.history_cap);
  SST_PRECISE float alpha = 1.0f / n;
  TemporalTexel result;
  SST_PRECISE vec3 d = direct + (c.direct - direct) * alpha;
  SST_PRECISE vec3 i = indirect + (c.indirect - indirect) * alpha;
  SST_PRECISE vec3 a = albedo + (c.albedo - albedo) * alpha;
  SST_PRECISE vec4 m = moments + (temporal_moments(c.luminance) - moments) * alpha;
  result.direct = d;
  result.indirect = i;
  result.albedo = a;
  result.pad1 = 0.0f;
  result.moments = m;
  result.frames = n;
  result.depth = c.depth;
  result.normal = c.normal;
  result.pad0 = 0.0f;
  return result;
}

SST_END

#endif  // SST_CORE_TEMPORAL_TEMPORAL_ACCUMULATE_H
