// ReSTIR's passes over an image that ReSTIR DI (Bitterli et al. 2020) and ReSTIR GI (Ouyang et
// al. 2021) share (shared C++/GLSL source: core/restir/restir.cpp on the CPU,
// gpu/shaders/restir.comp on the GPU). A round resamples at the first hits of one camera sample
// per pixel; its first pass, which draws each pixel's initial reservoir, is each method's own
// (core/restir/restir_di_stages.h, restir_gi_stages.h), then:
//
//   restir_temporal   (a frame's first round, after a frame) the pixel's reservoir merged with the
//                     previous frame's last where its point was seen, through the previous
//                     camera, its M capped
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
#include "core/accel/bvh_layout.h"
#include "core/math/accurate_math.h"
#include "core/math/geometric_similarity.h"
#include "core/pt/path_stages.h"
#include "core/render/pinhole.h"
#include "core/restir/reservoir.h"
#include "core/restir/restir_layout.h"
#include "core/rng/hash_rng.h"

#if !defined(RESTIR_CTX_PARAM) || !defined(RESTIR_CTX) || !defined(RESTIR_SURFACE) || !defined(RESTIR_RESERVOIR) || \
    !defined(RESTIR_HISTORY_SURFACE) || !defined(RESTIR_HISTORY_RESERVOIR)
#error "define the RESTIR_* hooks before including core/restir/restir_stages.h"
#endif
#if !defined(RAY_CTX_PARAM) || !defined(RAY_CTX) || !defined(RAY_INTERSECT) || !defined(RAY_OCCLUDED)
#error "define the RAY_* hooks before including core/restir/restir_stages.h"
#endif

SST_BEGIN

// A neighbour is merged only where its surface resembles the pixel's (Bitterli et al.'s test): the
// cosine between the shading normals above this, and the depths within this fraction of the
// pixel's depth. Elsewhere its samples would stand for a different integrand.
SST_CONSTANT float kRestirNormalCosine = 0.906f;  // 25 degrees
SST_CONSTANT float kRestirDepthFraction = 0.1f;

// The random streams of a round's stages (hash_rng's `stream`): the initial candidates, the
// temporal pass, then one per spatial pass; ReSTIR GI's secondary paths draw from a pixel sampler
// of their own seed.
SST_CONSTANT uint kRestirStreamInitial = 0x52455354u;  // "REST"
SST_CONSTANT uint kRestirStreamSpatial = 0x52455355u;
SST_CONSTANT uint kRestirStreamTemporal = 0x52455254u;  // "RERT"

// Two numbers in a fixed order (C++ leaves the order of a constructor's arguments open).
SST_FUNC vec2 restir_next2(SST_INOUT(HashRng) rng) {
  float u1 = hash_rng_next(rng);
  float u2 = hash_rng_next(rng);
  return vec2(u1, u2);
}

SST_FUNC RestirReservoir restir_reservoir_empty() {
  RestirReservoir r;
  r.light = LIGHT_NONE;
  r.b1 = 0.0f;
  r.b2 = 0.0f;
  r.weight = 0.0f;
  r.m = 0.0f;
  r.target = 0.0f;
  r.pad0 = 0u;
  r.pad1 = 0u;
  r.point = vec3(0.0f);
  r.offset = 0.0f;
  r.normal = vec3(0.0f);
  r.pad2 = 0.0f;
  r.radiance = vec3(0.0f);
  r.pad3 = 0.0f;
  return r;
}

// The first hit s of a camera ray along unit `dir` at distance `depth`; hit false: a miss.
SST_FUNC RestirSurface restir_surface(SST_IN(Surface) s, vec3 dir, float depth, bool hit) {
  RestirSurface r;
  r.p = s.p;
  r.offset = s.offset;
  r.ng = s.ng;
  r.metallic = s.metallic;
  r.ns = s.ns;
  r.roughness = s.roughness;
  r.base_color = s.base_color;
  r.hit = hit ? 1u : 0u;
  r.lift = s.lift;
  r.depth = depth;
  r.dir = dir;
  r.pad0 = 0.0f;
  return r;
}

// The sample (light entry `light`, barycentrics b on a triangle) seen from p, as a LightSample
// whose pdf makes f cos li / pdf the contribution per unit area of a triangle (pdf = d^2 /
// |cos_l|) and per light for a punctual one (pdf = 1). `area_per_solid_angle` receives |cos_l| /
// d^2 (1 for punctual lights): a solid-angle density times it is the density per unit area.
SST_FUNC bool restir_light_at(SCENE_CTX_PARAM LIGHT_CTX_PARAM vec3 p, uint light, vec2 b, SST_OUT(LightSample) ls,
                              SST_OUT(float) area_per_solid_angle) {
  ls = light_sample_none();
  area_per_solid_angle = 1.0f;
  if (light >= LIGHT_HEADER.distribution_size) return false;
  uint punctual_count = LIGHT_HEADER.punctual_count;
  if (light < punctual_count) return light_sample_punctual(p, LIGHT_PUNCTUAL(light), 1.0f, ls);
  uint tri = LIGHT_EMISSIVE(light - punctual_count).triangle;
  vec3 v0;
  vec3 v1;
  vec3 v2;
  light_triangle_vertices(SCENE_CTX tri, v0, v1, v2);
  float d2;
  float cos_light;
  if (!light_triangle_point(SCENE_CTX p, tri, v0, v1, v2, b, ls, d2, cos_light)) return false;
  ls.delta = false;
  SST_PRECISE float pdf = d2 / abs(cos_light);
  SST_PRECISE float g = abs(cos_light) / d2;
  ls.pdf = pdf;
  area_per_solid_angle = g;
  return is_finite(pdf) && pdf > 0.0f && is_finite(g) && g > 0.0f;
}

// A GI vertex (r.light RESTIR_GI_VERTEX) seen from p, as restir_light_at's LightSample: its
// radiance leaves from the side its normal faces only.
SST_FUNC bool restir_vertex_at(vec3 p, SST_IN(RestirReservoir) r, SST_OUT(LightSample) ls,
                               SST_OUT(float) area_per_solid_angle) {
  ls = light_sample_none();
  area_per_solid_angle = 1.0f;
  SST_PRECISE vec3 d = r.point - p;
  float d2 = dot3(d, d);
  if (!(d2 > 0.0f)) return false;
  ls.distance = sqrt(d2);
  SST_PRECISE vec3 wi = d / ls.distance;
  ls.wi = wi;
  float cos_y = -dot3(r.normal, ls.wi);
  if (!(cos_y > 0.0f)) return false;
  ls.li = r.radiance;
  ls.point = r.point;
  ls.normal = r.normal;
  ls.offset = r.offset;
  ls.delta = false;
  SST_PRECISE float pdf = d2 / cos_y;
  SST_PRECISE float g = cos_y / d2;
  ls.pdf = pdf;
  area_per_solid_angle = g;
  return is_finite(pdf) && pdf > 0.0f && is_finite(g) && g > 0.0f;
}

// Reservoir r's sample seen from p (restir_light_at or restir_vertex_at).
SST_FUNC bool restir_sample_at(SCENE_CTX_PARAM LIGHT_CTX_PARAM vec3 p, SST_IN(RestirReservoir) r,
                               SST_OUT(LightSample) ls, SST_OUT(float) area_per_solid_angle) {
  if (r.light == RESTIR_GI_VERTEX) return restir_vertex_at(p, r, ls, area_per_solid_angle);
  return restir_light_at(SCENE_CTX LIGHT_CTX p, r.light, vec2(r.b1, r.b2), ls, area_per_solid_angle);
}

// Surface s's unshadowed contribution from reservoir r's sample, in restir_sample_at's measure,
// with the shadow ray that decides it and the sample as a LightSample (wi, point, ...). Zero when
// the sample cannot contribute there.
SST_FUNC vec3 restir_contribution(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_IN(RestirSurface) s, bool diffuse_only,
                                  SST_IN(RestirReservoir) r, SST_OUT(ShadowRay) ray, SST_OUT(LightSample) ls,
                                  SST_OUT(float) area_per_solid_angle) {
  ray.origin = s.p;
  ray.dir = s.dir;
  ray.tmax = 0.0f;
  Basis basis;
  vec3 wo;
  if (!restir_sample_at(SCENE_CTX LIGHT_CTX s.p, r, ls, area_per_solid_angle)) return vec3(0.0f);
  if (!shading_frame(s.ns, s.ng, s.dir, basis, wo)) return vec3(0.0f);
  Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, diffuse_only);
  bool needs_ray;
  vec3 c = light_sample_unshadowed(s.p, s.ng, s.lift, s.offset, brdf, basis, wo, ls, false, ray, needs_ray);
  return needs_ray ? c : vec3(0.0f);
}

// restir_contribution's luminance, the target function p^.
SST_FUNC float restir_target(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_IN(RestirSurface) s, bool diffuse_only,
                             SST_IN(RestirReservoir) r) {
  ShadowRay ray;
  LightSample ls;
  float g;
  return luminance(restir_contribution(SCENE_CTX LIGHT_CTX s, diffuse_only, r, ray, ls, g));
}

// Whether reservoir r's sample reaches surface s: its contribution is positive and its shadow ray
// unoccluded (one ray, counted).
SST_FUNC bool restir_visible(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirSurface) s, bool diffuse_only,
                             SST_IN(RestirReservoir) r, SST_INOUT(PathCounters) counters) {
  ShadowRay ray;
  LightSample ls;
  float g;
  vec3 c = restir_contribution(SCENE_CTX LIGHT_CTX s, diffuse_only, r, ray, ls, g);
  if (!(luminance(c) > 0.0f)) return false;
  counters.shadow_rays += 1u;
  return !RAY_OCCLUDED(ray.origin, ray.dir, ray.tmax);
}

// Visibility reuse: a kept sample that does not reach s gets W = 0 (its M still counts).
SST_FUNC void restir_visibility_reuse(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirSurface) s,
                                      bool diffuse_only, SST_INOUT(RestirReservoir) r,
                                      SST_INOUT(PathCounters) counters) {
  if (r.light == LIGHT_NONE || !(r.weight > 0.0f)) return;
  if (!restir_visible(SCENE_CTX LIGHT_CTX RAY_CTX s, diffuse_only, r, counters)) r.weight = 0.0f;
}

// The first hit of pixel (x, y)'s camera ray for round `round` (the pixel sample index: the same
// ray as that sample of the methods' paths, so both see the same point).
SST_FUNC RestirSurface restir_camera(SCENE_CTX_PARAM RAY_CTX_PARAM SST_IN(ViewParams) view, uint x, uint y,
                                     uint round, SST_INOUT(PathCounters) counters) {
  PixelSampler ps = pixel_sampler(view.seed, y * view.width + x, round);
  vec3 dir = camera_sample_direction(view, x, y, ps);
  counters.primary_rays += 1u;
  BvhHit h = RAY_INTERSECT(view.eye, dir);
  if (h.triangle >= BVH_STACK_OVERFLOW) return restir_surface(surface_none(), dir, 0.0f, false);
  Surface s = make_surface(SCENE_CTX h.triangle, vec2(h.u, h.v), dir);
  return restir_surface(s, dir, h.t * length3(dir), true);
}

// Merging a pixel's own (canonical, c) reservoir with k others by pairwise MIS (Bitterli 2022,
// ch. 9; Wyman et al. 2023): each pair (c, i) splits 1/k by the balance heuristic over M-weighted
// targets,
//   m_i(x) = 1/k  M_i p^_i(x) / (M_i p^_i(x) + M_c p^_c(x)),  m_c(x) = sum_i 1/k - m_i(x),
// and each candidate x enters with weight m(x) p^_c(x) W. Unlike 1/Z (Bitterli et al. 2020,
// Alg. 6), a neighbour's sample lands with little weight where the neighbour's target was far
// larger than the pixel's would be (near a light's edge its W carried fireflies a hundred times
// the pixel's value). Unbiased: the other pixel's p^_i(x_c) counts only where x_c reaches it (one
// shadow ray each), as its own visibility reuse would have zeroed it elsewhere; biased: without
// the rays, so the pixel's sample keeps less weight across shadow edges than it should.
struct RestirMerge {
  RestirReservoir r;    // the kept sample, its target p^_c
  float weight_sum;
  float m_canonical;    // m_c(x_c), summed over the pairs
  float m;              // the merged M
};

SST_FUNC RestirMerge restir_merge_begin(SST_IN(RestirReservoir) canonical) {
  RestirMerge g;
  g.r = restir_reservoir_empty();
  g.weight_sum = 0.0f;
  g.m_canonical = 0.0f;
  g.m = canonical.m;
  return g;
}

// Pair (c, i): reservoir rn of the pixel whose first hit is sn, one of k, with u uniform.
SST_FUNC void restir_merge_pair(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirSurface) s,
                                SST_IN(RestirReservoir) canonical, SST_IN(RestirSurface) sn,
                                SST_IN(RestirReservoir) rn, float inv_k, bool diffuse_only, bool unbiased, float u,
                                SST_INOUT(RestirMerge) g, SST_INOUT(PathCounters) counters) {
  g.m += rn.m;
  // The other pixel's sample x_i at this one: m_i(x_i) p^_c(x_i) W_i.
  if (rn.light != LIGHT_NONE) {
    float target = restir_target(SCENE_CTX LIGHT_CTX s, diffuse_only, rn);
    SST_PRECISE float mi_target = rn.m * rn.target;
    SST_PRECISE float mc_at = canonical.m * target;
    SST_PRECISE float denominator = mi_target + mc_at;
    SST_PRECISE float w = denominator > 0.0f ? inv_k * mi_target / denominator * target * rn.weight : 0.0f;
    if (reservoir_accept(g.weight_sum, w, u)) {
      g.r = rn;
      g.r.target = target;
    }
  }
  // The canonical sample x_c at the other pixel: its share of the pair.
  SST_PRECISE float mc_target = canonical.m * canonical.target;
  if (canonical.light != LIGHT_NONE && mc_target > 0.0f) {
    float t_i = restir_target(SCENE_CTX LIGHT_CTX sn, diffuse_only, canonical);
    if (t_i > 0.0f && unbiased && !restir_visible(SCENE_CTX LIGHT_CTX RAY_CTX sn, diffuse_only, canonical, counters))
      t_i = 0.0f;
    SST_PRECISE float mi_at = rn.m * t_i;
    SST_PRECISE float share = inv_k * mc_target / (mc_target + mi_at);
    g.m_canonical += share;
  }
}

// The canonical sample streamed last (u uniform), then the kept sample's W and visibility reuse.
SST_FUNC RestirReservoir restir_merge_end(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirSurface) s,
                                          SST_IN(RestirReservoir) canonical, bool diffuse_only, float u,
                                          SST_INOUT(RestirMerge) g, SST_INOUT(PathCounters) counters) {
  SST_PRECISE float w_canonical = g.m_canonical * canonical.target * canonical.weight;
  if (canonical.light != LIGHT_NONE && reservoir_accept(g.weight_sum, w_canonical, u)) g.r = canonical;
  RestirReservoir r = g.r;
  r.m = g.m;
  r.weight = reservoir_contribution_weight(g.weight_sum, 1.0f, r.target);
  restir_visibility_reuse(SCENE_CTX LIGHT_CTX RAY_CTX s, diffuse_only, r, counters);
  return r;
}

// Whether the first hit sn may lend its reservoir to s: both hit, and the shading normals and the
// depths (`depth_n`: sn's point's distance from the camera s is seen by) agree.
SST_FUNC bool restir_similar(SST_IN(RestirSurface) s, SST_IN(RestirSurface) sn, float depth_n) {
  return sn.hit != 0u &&
         geometrically_similar(s.ns, sn.ns, abs(depth_n - s.depth), kRestirNormalCosine, kRestirDepthFraction * s.depth);
}

// Pixel (x, y)'s temporal pass: its reservoir merged with the one the previous frame's last round
// left where its point was (seen by that round's camera `previous`), whose M is capped at `cap`
// times its own so that old samples cannot dominate for ever. The history's pixel is the one its
// camera saw the point through, if its surface resembles this one (a static scene's point, or one
// that moved little); then the history is evaluated at its own surface, as it was.
SST_FUNC RestirReservoir restir_temporal(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM RESTIR_CTX_PARAM uint x, uint y,
                                         SST_IN(ViewParams) previous, bool diffuse_only, float cap, bool unbiased,
                                         SST_INOUT(HashRng) rng, SST_INOUT(PathCounters) counters) {
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

// The round's estimate at s (DI: the direct light; GI: the indirect light): the kept sample's
// contribution times W.
SST_FUNC vec3 restir_shade(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_IN(RestirSurface) s, bool diffuse_only,
                           SST_IN(RestirReservoir) r) {
  if (s.hit == 0u || r.light == LIGHT_NONE || !(r.weight > 0.0f)) return vec3(0.0f);
  ShadowRay ray;
  LightSample ls;
  float g;
  vec3 c = restir_contribution(SCENE_CTX LIGHT_CTX s, diffuse_only, r, ray, ls, g);
  return product_exact(c, vec3(r.weight));
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
                         push.temporal_cap, (push.flags & RESTIR_UNBIASED) != 0u, rng, counters);
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
