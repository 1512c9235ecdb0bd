// ReSTIR's passes over an image that ReSTIR DI (Bitterli et al. 2020) and ReSTIR GI (Ouyang et
// al. 2021) share (shared C++/GLSL source: core/restir/restir.cpp on the CPU,
// gpu/shaders/restir.comp on the GPU). A round resamples at the first hits of one camera sample
// per pixel; its first pass, which draws each pixel's initial reservoir, is each method's own
// (core/restir/restir_di_stages.h, restir_gi_stages.h), then:
//
//   restir_temporal   (a frame's first round, after a frame) the pixel's reservoir merged with the
//                     previous frame's last where its point was seen, through the previous
//                     camera, its M capped; after the scene moved, ReSTIR GI's history validated
//                     first (restir_gi_validate)
//   restir_spatial    (each spatial pass) the pixel's reservoir merged with up to `neighbours`
//                     reservoirs of similar pixels within `radius` by pairwise MIS (unbiased: a
//                     neighbour's weight for the pixel's sample checked with a shadow ray;
//                     biased: without), then visibility reuse again
//   restir_shade      the kept sample's contribution times W (visibility is already in W)
//
// A sample is a point: on a light (DI: the light's entry and, on an emissive triangle, the
// barycentrics; punctual lights are their own measure) or a secondary surface (GI: the vertex and
// the radiance it sends toward the pixel that found it, RESTIR_GI_VERTEX). The target function p^
// is the luminance of the unshadowed contribution per unit area of that point's surface,
// f cos_i L cos_y / d^2, so a sample means the same thing at every pixel and moves between pixels
// without a Jacobian; candidates' source densities are converted to that measure (solid angle x
// cos_y / d^2). A GI vertex's radiance is reused toward other pixels as it was estimated: exact for
// a diffuse vertex, an approximation on glossy ones.
//
// Hooks, besides the scene's (core/shading/surface_eval.h), the lights' (core/lights/
// light_sample.h) and the ray queries (core/pt/trace_path.h lists them):
//   RESTIR_CTX_PARAM / RESTIR_CTX  the context parameter and argument (empty in GLSL)
//   RESTIR_SURFACE(i)              RestirSurface: pixel i's first hit in this round
//   RESTIR_RESERVOIR(i)            RestirReservoir: pixel i's reservoir, as the previous stage left it
//   RESTIR_HISTORY_SURFACE(i)      RestirSurface: pixel i's first hit in the previous round
//   RESTIR_HISTORY_RESERVOIR(i)    RestirReservoir: pixel i's final reservoir of the previous round
#ifndef SST_CORE_RESTIR_RESTIR_STAGES_H
#define SST_CORE_RESTIR_RESTIR_STAGES_H
#include "core/restir/restir_gi_stages.h"
#include "core/restir/restir_resampling.h"

#if !defined(RESTIR_CTX_PARAM) || !defined(RESTIR_CTX) || !defined(RESTIR_SURFACE) || !defined(RESTIR_RESERVOIR) || \
    !defined(RESTIR_HISTORY_SURFACE) || !defined(RESTIR_HISTORY_RESERVOIR)
#error "define the RESTIR_* hooks before including core/restir/restir_stages.h"
#endif

SST_BEGIN

// Pixel (x, y)'s temporal pass: its reservoir merged with the one the previous frame's last round
// left where its point was (seen by that round's camera `previous`), whose M is capped at `cap`
// times its own so that old samples cannot dominate for ever. The history's pixel is the one its
// camera saw the point through, if its surface resembles this one (a static scene's point, or one
// that moved little); then the history is evaluated at its own surface, as it was, or, when the
// scene moved since (`posed`), as the scene is now: a light's sample names its light and point on
// it, which moved with it, and a GI vertex was validated (restir_gi_validate), so the pair's two
// MIS weights take the history's target from one function.
SST_FUNC RestirReservoir restir_temporal(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM RESTIR_CTX_PARAM uint x, uint y,
                                         SST_IN(ViewParams) previous, bool diffuse_only, float cap, bool unbiased,
                                         bool posed, SST_INOUT(HashRng) rng, SST_INOUT(PathCounters) counters) {
  uint q = y * previous.width + x;
  RestirSurface s = RESTIR_SURFACE(q);
  RestirReservoir canonical = RESTIR_RESERVOIR(q);
  float u_pair = hash_rng_next(rng);
  float u_canonical = hash_rng_next(rng);
  if (s.hit == 0u) return canonical;
  // Where the previous camera saw s.p (pinhole_direction inverted).
  SST_PRECISE vec3 d = s.p - previous.eye;
  float z = dot3(d, previous.forward);
  if (!(z > 0.0f)) return canonical;
  SST_PRECISE float sx = dot3(d, previous.right) / z / (previous.tan_half_y * previous.aspect);
  SST_PRECISE float sy = dot3(d, previous.up) / z / previous.tan_half_y;
  SST_PRECISE float px = (sx + 1.0f) * 0.5f * float(previous.width);
  SST_PRECISE float py = (1.0f - sy) * 0.5f * float(previous.height);
  if (!(px >= 0.0f && py >= 0.0f && px < float(previous.width) && py < float(previous.height))) return canonical;
  uint h = uint(py) * previous.width + uint(px);
  RestirSurface sh = RESTIR_HISTORY_SURFACE(h);
  if (!restir_similar(s, sh, length3(d))) return canonical;
  RestirReservoir rh = RESTIR_HISTORY_RESERVOIR(h);
  rh.m = min(rh.m, cap * canonical.m);
  if (posed && rh.light != LIGHT_NONE) {
    rh.target = restir_target(SCENE_CTX LIGHT_CTX sh, diffuse_only, rh);
    // Unbiased, the canonical sample's weight takes the history to produce only what sh sees in
    // the scene as it is now (restir_merge_pair's shadow ray), so the history's own sample must
    // reach sh now too, not only in the pose it was drawn in.
    if (unbiased && rh.weight > 0.0f && !restir_visible(SCENE_CTX LIGHT_CTX RAY_CTX sh, diffuse_only, rh, counters))
      rh.weight = 0.0f;
  }
  RestirMerge g = restir_merge_begin(canonical);
  restir_merge_pair(SCENE_CTX LIGHT_CTX RAY_CTX s, canonical, sh, rh, 1.0f, diffuse_only, unbiased, u_pair, g, counters);
  return restir_merge_end(SCENE_CTX LIGHT_CTX RAY_CTX s, canonical, diffuse_only, u_canonical, g, counters);
}

// Pixel (x, y)'s spatial pass over the reservoirs RESTIR_RESERVOIR left by the previous stage: its
// own merged with those of up to `neighbours` similar pixels drawn uniformly within `radius`.
SST_FUNC RestirReservoir restir_spatial(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM RESTIR_CTX_PARAM uint x, uint y,
                                        uint width, uint height, bool diffuse_only, uint neighbours, float radius,
                                        bool unbiased, SST_INOUT(HashRng) rng, SST_INOUT(PathCounters) counters) {
  uint q = y * width + x;
  RestirSurface s = RESTIR_SURFACE(q);
  RestirReservoir canonical = RESTIR_RESERVOIR(q);
  if (s.hit == 0u) return restir_reservoir_empty();
  uint merged[RESTIR_MAX_NEIGHBOURS];
  uint k = 0u;
  for (uint j = 0u; j < neighbours && j < RESTIR_MAX_NEIGHBOURS; ++j) {
    float u_radius = hash_rng_next(rng);
    float u_angle = hash_rng_next(rng);
    SST_PRECISE float rho = radius * sqrt(u_radius);
    SST_PRECISE float phi = 2.0f * kPi * u_angle;
    SST_PRECISE float fx = float(x) + rho * accurate_cos(phi);
    SST_PRECISE float fy = float(y) + rho * accurate_sin(phi);
    int nx = int(floor(fx + 0.5f));
    int ny = int(floor(fy + 0.5f));
    if (nx < 0 || ny < 0 || nx >= int(width) || ny >= int(height) || (uint(nx) == x && uint(ny) == y)) continue;
    uint n = uint(ny) * width + uint(nx);
    RestirSurface sn = RESTIR_SURFACE(n);
    if (!restir_similar(s, sn, sn.depth)) continue;
    merged[k] = n;
    k += 1u;
  }
  if (k == 0u) return canonical;
  float inv_k = 1.0f / float(k);
  RestirMerge g = restir_merge_begin(canonical);
  for (uint i = 0u; i < k; ++i) {
    float u = hash_rng_next(rng);
    restir_merge_pair(SCENE_CTX LIGHT_CTX RAY_CTX s, canonical, RESTIR_SURFACE(merged[i]), RESTIR_RESERVOIR(merged[i]),
                      inv_k, diffuse_only, unbiased, u, g, counters);
  }
  float u_canonical = hash_rng_next(rng);
  return restir_merge_end(SCENE_CTX LIGHT_CTX RAY_CTX s, canonical, diffuse_only, u_canonical, g, counters);
}

// ---- one pixel of each pass, as both schedules run it ------------------------------------------
// Each takes the round's push constants (RestirPush: view.sample_offset is the round, `pass` the
// spatial pass) and draws from its own random stream.

// A pixel's sums before a frame's first round.
SST_FUNC RestirTexel restir_texel_empty() {
  RestirTexel t;
  t.direct = vec3(0.0f);
  t.primary_rays = 0u;
  t.shadow_rays = 0u;
  t.bounce_rays = 0u;
  t.nonfinite = 0u;
  t.pad0 = 0u;
  return t;
}

// The rays a pass traced for the pixel, added to its sums.
SST_FUNC void restir_texel_count(SST_INOUT(RestirTexel) t, SST_IN(PathCounters) c) {
  t.primary_rays += c.primary_rays;
  t.shadow_rays += c.shadow_rays;
  t.bounce_rays += c.bounce_rays;
}

// A round's estimate d added to the pixel's sums. A NaN or Inf estimate is a bug to find, not a
// pixel to show: it is dropped and counted.
SST_FUNC void restir_texel_add(SST_INOUT(RestirTexel) t, vec3 d) {
  if (!is_finite3(d)) {
    t.nonfinite += 1u;
    return;
  }
  SST_PRECISE vec3 sum = t.direct + d;
  t.direct = sum;
}

// Pixel (x, y)'s temporal pass (restir_temporal) over the history seen by `previous`.
SST_FUNC RestirReservoir restir_temporal_pixel(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM RESTIR_CTX_PARAM
                                               SST_IN(RestirPush) push, uint x, uint y, SST_IN(ViewParams) previous,
                                               SST_INOUT(PathCounters) counters) {
  HashRng rng = hash_rng(push.view.seed, y * push.view.width + x, push.view.sample_offset, kRestirStreamTemporal);
  return restir_temporal(SCENE_CTX LIGHT_CTX RAY_CTX RESTIR_CTX x, y, previous, (push.flags & RESTIR_DIFFUSE_ONLY) != 0u,
                         push.temporal_cap, (push.flags & RESTIR_UNBIASED) != 0u, (push.flags & RESTIR_POSED) != 0u,
                         rng, counters);
}

// The history's pixel (x, y) validated (restir_gi_validate) for the round of `push`, the first
// after the scene moved.
SST_FUNC RestirReservoir restir_gi_validate_pixel(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM RESTIR_CTX_PARAM
                                                  SST_IN(RestirPush) push, uint x, uint y,
                                                  SST_INOUT(PathCounters) counters) {
  uint h = y * push.view.width + x;
  PixelSampler ps = pixel_sampler(push.view.seed ^ kRestirGiValidationSeed, h, push.view.sample_offset);
  return restir_gi_validate(SCENE_CTX LIGHT_CTX RAY_CTX RESTIR_HISTORY_SURFACE(h), RESTIR_HISTORY_RESERVOIR(h),
                            (push.flags & RESTIR_DIFFUSE_ONLY) != 0u, push.max_bounces, push.rr_min_bounces, ps,
                            counters);
}

// Pixel (x, y)'s spatial pass number push.pass (restir_spatial).
SST_FUNC RestirReservoir restir_spatial_pixel(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM RESTIR_CTX_PARAM
                                              SST_IN(RestirPush) push, uint x, uint y,
                                              SST_INOUT(PathCounters) counters) {
  HashRng rng = hash_rng(push.view.seed, y * push.view.width + x, push.view.sample_offset,
                         kRestirStreamSpatial + push.pass);
  return restir_spatial(SCENE_CTX LIGHT_CTX RAY_CTX RESTIR_CTX x, y, push.view.width, push.view.height,
                        (push.flags & RESTIR_DIFFUSE_ONLY) != 0u, push.neighbours, push.radius,
                        (push.flags & RESTIR_UNBIASED) != 0u, rng, counters);
}

SST_END

#endif  // SST_CORE_RESTIR_RESTIR_STAGES_H
