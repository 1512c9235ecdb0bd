// GI-1.0's per-pixel output (docs/design/gi10.md): each pixel's irradiance from up to four screen
// probes, the method's own denoiser (reprojected history of variable length and a blur that
// shrinks as the history grows), and the image the next frame's feedback reads.
#ifndef SST_CORE_GI10_GI10_RESOLVE_H
#define SST_CORE_GI10_GI10_RESOLVE_H
#include "core/gi10/gi10_probes.h"

SST_BEGIN

// ---- S19: each pixel's irradiance from up to four probes ------------------------------------------
// The irradiance at normal ns from the probe at `seed`: from its L2 SH (the paper), or, with
// GI10_IRRADIANCE_TEXELS, the clamped cosine integrated over its 64 texels at their centres, which
// leaves out the SH's truncation and weight (the texels of a reprojected probe also carry its
// parallax, which its copied SH do not).
SST_FUNC vec3 gi_probe_irradiance(GI_CTX_PARAM uvec2 seed, vec3 ns) {
  uint tile = gi_tile_of(GF, seed);
  SST_PRECISE vec3 e = vec3(0.0f);
  if ((GF.flags & GI10_IRRADIANCE_TEXELS) != 0u) {
    GiFrame fq = gi_frame(gi_pixel(GI_CTX gi_parity(GF), gi_pixel_index(GF, seed)).ng);
    uint base = gi_parity(GF) * gi_tiles(GF) * 64u + tile * 64u;
    for (uint c = 0u; c < 64u; ++c)
      e += gi_rgb(GI_RADIANCE(base + c)) * (max(dot3(gi_texel_direction(fq, c), ns), 0.0f) * (2.0f * kPi / 64.0f));
    return e;
  }
  uint base = gi_parity(GF) * gi_tiles(GF) * 9u + tile * 9u;
  for (uint k = 0u; k < 9u; ++k) e += gi_rgb(GI_SH(base + k)) * gi_sh_cosine(k, ns);
  return max3(e, vec3(0.0f));
}

SST_FUNC void gi_stage_interpolate(GI_CTX_PARAM uint index) {
  uint cur = gi_parity(GF);
  Gi10Pixel px = gi_pixel(GI_CTX cur, index);
  vec4 out_value = vec4(0.0f);
  if (!gi_sky(px)) {
    uvec2 p = uvec2(index % GF.width, index / GF.width);
    float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe);
    HashRng rng = gi_rng(GF, GI10_STAGE_INTERPOLATE, index);
    float jx = hash_rng_next(rng);
    float jy = hash_rng_next(rng);
    ivec2 j = ivec2(int((2.0f * jx - 1.0f) * GF.interpolation_jitter), int((2.0f * jy - 1.0f) * GF.interpolation_jitter));
    ivec2 pj = clamp(ivec2(int(p.x), int(p.y)) + j, ivec2(0, 0), ivec2(int(GF.width) - 1, int(GF.height) - 1));
    Gi10Pixel pjx = gi_pixel(GI_CTX cur, gi_pixel_index(GF, uvec2(uint(pj.x), uint(pj.y))));
    uvec2 search = p;
    if (!gi_sky(pjx) && abs(dot3(pjx.position - px.position, px.ng)) < 0.5f * cs) search = uvec2(uint(pj.x), uint(pj.y));
    uint q[4];
    q[0] = gi_find_probe(GI_CTX search, ivec2(0, 0));
    if (q[0] != kGiNoProbe) {
      uvec2 s0 = gi_unpack(q[0]);
      ivec2 o = ivec2(search.x < s0.x ? -1 : 1, search.y < s0.y ? -1 : 1);
      q[1] = gi_find_probe(GI_CTX search, ivec2(o.x, 0));
      q[2] = gi_find_probe(GI_CTX search, ivec2(0, o.y));
      q[3] = gi_find_probe(GI_CTX search, o);
      float w[4];
      SST_PRECISE float wsum = 0.0f;
      float found = 0.0f;
      for (uint i = 0u; i < 4u; ++i) {
        w[i] = -1.0f;  // -1: no probe, or a duplicate of an earlier one
        if (q[i] == kGiNoProbe) continue;
        bool duplicate = false;
        for (uint k = 0u; k < i; ++k) duplicate = duplicate || q[k] == q[i];
        if (duplicate) continue;
        Gi10Pixel pq = gi_pixel(GI_CTX cur, gi_pixel_index(GF, gi_unpack(q[i])));
        w[i] = 0.0f;
        found += 1.0f;
        if (abs(dot3(pq.position - px.position, px.ng)) > cs) continue;
        SST_PRECISE float wq = gi_pow8(gi_saturate(1.0f - abs(pq.depth - px.depth) / px.depth) * max(dot3(px.ng, pq.ng), 0.0f));
        w[i] = wq;
        wsum += w[i];
      }
      // With no probe on the pixel's surface, every found probe counts alike ("relaxed"), and the
      // denoiser is told not to trust the sample (hint 0).
      float hint = wsum > 0.0f ? 1.0f : 0.0f;
      if (!(wsum > 0.0f)) GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_RELAXED), 1u);
      SST_PRECISE vec3 e = vec3(0.0f);
      for (uint i = 0u; i < 4u; ++i) {
        if (w[i] < 0.0f) continue;
        float wi = wsum > 0.0f ? w[i] / wsum : 1.0f / found;
        if (wi > 0.0f) {
          e += wi * gi_probe_irradiance(GI_CTX gi_unpack(q[i]), gi_ns(px));
        }
      }
      out_value = gi_vec4(e, hint);
    } else {
      GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_NO_PROBE), 1u);
    }
  }
  GI_DENOISE(index) = out_value;
}

// ---- S20: GI-1.0's denoiser: reprojected history with a variable length, then a blur whose radius
// shrinks as the history grows --------------------------------------------------------------------
SST_FUNC float gi_history_count(vec4 h) { return abs(h.w); }
SST_FUNC vec3 gi_history_mean(vec4 h) { return gi_rgb(h) / max(abs(h.w), 1.0f); }

SST_FUNC void gi_stage_denoise_reproject(GI_CTX_PARAM uint index) {
  uint cur = gi_parity(GF);
  uint prev = cur ^ 1u;
  uint n = gi_pixels(GF);
  Gi10Pixel px = gi_pixel(GI_CTX cur, index);
  vec4 e = GI_DENOISE(index);
  SST_PRECISE vec4 h = vec4(0.0f);
  SST_PRECISE float delta = 0.0f;
  SST_PRECISE float beta = 1.0f;
  uvec2 p = uvec2(index % GF.width, index / GF.width);
  if (gi_sky(px)) {
    GI_DENOISE((1u + cur) * n + index) = vec4(0.0f);
    GI_AUX(cur * n + index) = vec4(0.0f, -1.0f, -1.0f, 0.0f);
    return;
  }
  vec2 q;
  float distance;
  if (GF.has_history != 0u && project_to_pixel(GF.previous_view, px.position, q, distance) && q.x >= 0.0f &&
      q.y >= 0.0f && q.x < float(GF.width) && q.y < float(GF.height)) {
    vec3 v = normalize3(GF.view.eye - px.position);
    SST_PRECISE float graze = 1.0f - max(dot3(v, gi_ns(px)), 0.0f);
    SST_PRECISE float graze2 = graze * graze;
    SST_PRECISE float cs = gi_cell_size(GF.view.eye, px.position, GF.k_probe) * (1.0f + 4.0f * graze2 * graze2 * graze2);
    SST_PRECISE vec4 hs = vec4(0.0f);
    SST_PRECISE float ds = 0.0f;
    SST_PRECISE float ws = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        int sx = int(floor(q.x)) + dx;
        int sy = int(floor(q.y)) + dy;
        if (sx < 0 || sy < 0 || sx >= int(GF.width) || sy >= int(GF.height)) continue;
        uint si = uint(sy) * GF.width + uint(sx);
        vec4 hp = GI_DENOISE((1u + prev) * n + si);
        if (hp.w < 1.0f) continue;
        Gi10Pixel pp = gi_pixel(GI_CTX prev, si);
        if (gi_sky(pp) || !(length3(px.position - pp.position) < cs) || !(dot3(gi_ns(px), gi_ns(pp)) > 0.95f)) continue;
        SST_PRECISE float ddx = float(sx) + 0.5f - q.x;
        SST_PRECISE float ddy = float(sy) + 0.5f - q.y;
        SST_PRECISE float wt = gi_saturate(1.0f - sqrt(ddx * ddx + ddy * ddy) / 1.41421356f);
        hs += hp * wt;
        ds += GI_AUX(prev * n + si).x * wt;
        ws += wt;
      }
    }
    if (ws > 0.0f) {
      h = hs / ws;
      delta = ds / ws;
    }
    if (e.w > 0.0f) {
      float lh = luminance(gi_history_mean(h));
      delta = delta + (luminance(gi_rgb(e)) - lh - delta) * 0.125f;
      beta = gi_saturate(1.0f - abs(delta) / max(lh, 1e-4f));
    }
  }
  float mask = max(8.0f - gi_history_count(h), 0.0f);
  // A trusted sample (hint 1) is added to the history (replacing relaxed ones); a relaxed one only
  // where nothing trusted is kept, counted negative.
  if (e.w > 0.0f) {
    if (h.w < 0.0f) h = vec4(0.0f);
    h += gi_vec4(gi_rgb(e), 1.0f);
  } else if (h.w < 1.0f) {
    h += gi_vec4(gi_rgb(e), -1.0f);
  }
  SST_PRECISE float u = (float(p.x) + 0.5f) / float(GF.width);
  SST_PRECISE float v = (float(p.y) + 0.5f) / float(GF.height);
  SST_PRECISE float vign = sqrt(sqrt(max(15.0f * u * (1.0f - v) * v * (1.0f - u), 0.0f)));
  float count = gi_history_count(h);
  SST_PRECISE float cap = max((4.0f + (GF.denoise_history * min(count, 8.0f) - 4.0f) * beta) * vign, 1.0f);
  if (count > cap) h = h * (cap / count);
  GI_DENOISE((1u + cur) * n + index) = h;
  GI_AUX(cur * n + index) = vec4(delta, mask, mask, 0.0f);
}

// Dilates the blur mask over 9x9 pixels with a linear falloff; counts the blur's work.
SST_FUNC void gi_stage_blur_mask(GI_CTX_PARAM uint index) {
  uint cur = gi_parity(GF);
  uint n = gi_pixels(GF);
  vec4 aux = GI_AUX(cur * n + index);
  if (aux.y < 0.0f) return;  // sky
  int px = int(index % GF.width);
  int py = int(index / GF.width);
  bool capsaicin = (GF.flags & GI10_BLUR_MASK_CAPSAICIN) != 0u;
  float m = aux.y;
  for (int dy = -4; dy <= 4; ++dy) {
    for (int dx = -4; dx <= 4; ++dx) {
      if (capsaicin ? (dx == 0 || dy == 0) : (dx == 0 && dy == 0)) continue;
      int sx = px + dx;
      int sy = py + dy;
      if (sx < 0 || sy < 0 || sx >= int(GF.width) || sy >= int(GF.height)) continue;
      float tap = GI_AUX(cur * n + uint(sy) * GF.width + uint(sx)).y;
      SST_PRECISE float falloff = gi_saturate(1.0f - sqrt(float(dx * dx + dy * dy)) / (4.0f * 1.41421356f));
      SST_PRECISE float rounded = floor(tap * falloff + 0.5f);
      m = max(m, rounded);
    }
  }
  aux.z = m;
  GI_AUX(cur * n + index) = aux;
  uint r = uint(m);
  GI_ATOMIC_ADD(GI_COUNTERS(GI10_COUNT_BLUR_WORK), (2u * r + 1u) * (2u * r + 1u));
}

// One pass of the separable blur (pass 0 along x from the history into the scratch, pass 1 along y
// back into the history), of radius shrinking with the history and with the frame's total work.
// Pass 1 writes E_out, the history's mean.
SST_FUNC void gi_stage_filter_gi(GI_CTX_PARAM uint pass, uint index) {
  uint cur = gi_parity(GF);
  uint n = gi_pixels(GF);
  uint history_base = (1u + cur) * n;  // in DENOISE
  uint scratch = 2u * n;          // in AUX
  vec4 h = pass == 0u ? GI_DENOISE(history_base + index) : GI_AUX(scratch + index);
  float m = GI_AUX(cur * n + index).z;
  Gi10Pixel px = gi_pixel(GI_CTX cur, index);
  int radius = 0;
  if (m > 0.0f) {
    float work = float(GI_COUNTERS(GI10_COUNT_BLUR_WORK)) / float(n);
    SST_PRECISE float off = max(0.5f * sqrt(max(work - 25.0f, 0.0f)) - 1.0f, 0.0f);
    radius = int(max(m - off, 1.0f) + 0.5f);
  }
  vec4 result = h;
  if (radius > 0 && !gi_sky(px)) {
    bool history = h.w > 0.0f;
    float k = history ? 200.0f : 20.0f;
    SST_PRECISE vec3 sum = gi_history_mean(h);
    SST_PRECISE float wsum = 1.0f;
    int x = int(index % GF.width);
    int y = int(index / GF.width);
    for (int r = -radius; r <= radius; ++r) {
      int sx = pass == 0u ? x + r : x;
      int sy = pass == 0u ? y : y + r;
      if (sx < 0 || sy < 0 || sx >= int(GF.width) || sy >= int(GF.height)) continue;
      uint si = uint(sy) * GF.width + uint(sx);
      vec4 hq = pass == 0u ? GI_DENOISE(history_base + si) : GI_AUX(scratch + si);
      if (!(hq.w > 0.0f)) continue;
      Gi10Pixel pq = gi_pixel(GI_CTX cur, si);
      if (gi_sky(pq)) continue;
      SST_PRECISE float w = gi_exp2_negative(-k * abs(1.0f - px.depth / pq.depth));
      if (history) {
        float c = max(dot3(gi_ns(px), gi_ns(pq)), 0.0f);
        w *= (c * c) * (c * c);
      }
      sum += gi_history_mean(hq) * w;
      wsum += w;
    }
    SST_PRECISE vec3 scaled = sum / wsum * max(abs(h.w), 1.0f);
    result = gi_vec4(scaled, h.w);
  }
  if (pass == 0u) {
    GI_AUX(scratch + index) = result;
  } else {
    GI_DENOISE(history_base + index) = result;
    GI_OUTPUT(index) = gi_vec4(gi_history_mean(result), h.w);
  }
}

// The radiance the next frame's feedback reads: this frame's image without the emission seen (the
// direct pass and the caches both add it otherwise). The host has put the image in FEEDBACK.
SST_FUNC void gi_stage_feedback_image(GI_CTX_PARAM uint index) {
  vec3 c = gi_rgb(GI_FEEDBACK(index)) - gi_rgb(GI_EMISSION(index));
  GI_FEEDBACK(index) = gi_vec4(max3(c, vec3(0.0f)), 0.0f);
}

SST_END

#endif  // SST_CORE_GI10_GI10_RESOLVE_H
