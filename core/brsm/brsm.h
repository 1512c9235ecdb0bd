// VPLs from Bidirectional Reflective Shadow Maps (BRSM; Ritschel et al. 2011, with the hybrid
// thesis's changes, its ch. 4.1; docs/design/brsm.md), shared C++/GLSL source: the CPU's executor
// is core/brsm/brsm_generator.cpp, the GPU's gpu/brsm_pass.cpp with gpu/shaders/brsm.comp.
//
// A map covers a range of lights (BrsmMap). Each of its R x R texels casts one ray from a light:
// the texel's cell of the light's emission parameters (light_emit: the direction for point, spot
// and emissive-triangle lights, the position on the focus discs for directional ones), jittered,
// the other parameters random. Its first diffuse hit is the texel's potential VPL (pVPL), whose
// intensity stands for the texel's cell alone, so the pVPLs of a map are a stratified instant-
// radiosity set of one-bounce light. Each pVPL is weighed by its expected contribution to what the
// camera sees (brsm_importance), the weights are filtered edge-aware (brsm_filtered) and summed into
// a mip chain, and the map's VPLs are drawn by hierarchical warping of a rotated Hammersley set
// down that chain (brsm_warp). A drawn pVPL's intensity is divided by its draw count times its
// probability, so the VPL set's expected one-bounce light is the pVPLs', whatever the weights; a
// share `power_fraction` of the probability follows the pVPLs' power alone, so that no pVPL that
// lights something is never drawn (a weight estimated from a few G-buffer samples can be 0 for a
// pVPL that lights what the camera sees: the thesis's near samples alone missed 14% of the
// staircase's one-bounce light).
//
// Hooks, besides the scene's, the lights' and the ray queries (core/pt/trace_path.h lists them):
//   BRSM_CTX_PARAM / BRSM_CTX   the context parameter and argument (empty in GLSL)
//   BRSM_GSAMPLE(i)             BrsmGSample: G-buffer pixel i (row-major)
//   BRSM_TEXEL(i)               BrsmTexel: texel i of the current map (row-major)
//   BRSM_MIP(i)                 vec2: entry i of the current map's mip chain (brsm_mip_offset):
//                               (filtered importance, pVPL luminance), summed over the texels below
//   BRSM_STORE_GSAMPLE(i, g)    and BRSM_STORE_TEXEL(i, t), BRSM_STORE_MIP(i, m), BRSM_STORE_VPL(i, v):
//                               what brsm_stage_step writes (VPL i of the whole set)
#ifndef SST_CORE_BRSM_BRSM_H
#define SST_CORE_BRSM_BRSM_H
#include "core/accel/bvh_layout.h"
#include "core/accel/ray_offset.h"
#include "core/render/pinhole.h"
#include "core/render/reprojection.h"
#include "core/rng/hash_rng.h"
#include "core/sampling/sampling.h"
#include "core/brsm/brsm_layout.h"
#include "core/vpl/vpl_albedo.h"
#include "core/vpl/vpl.h"

#if !defined(BRSM_CTX_PARAM) || !defined(BRSM_CTX) || !defined(BRSM_GSAMPLE) || !defined(BRSM_TEXEL) || \
    !defined(BRSM_MIP) || !defined(BRSM_STORE_GSAMPLE) || !defined(BRSM_STORE_TEXEL) || !defined(BRSM_STORE_MIP) || \
    !defined(BRSM_STORE_VPL)
#error "define the BRSM_* hooks before including core/brsm/brsm.h"
#endif

SST_BEGIN

SST_FUNC vec2 brsm_next_2d(SST_INOUT(HashRng) rng) {
  float x = hash_rng_next(rng);
  float y = hash_rng_next(rng);
  return vec2(x, y);
}

// The G-buffer samples of a pVPL lie at distances from it between brsm_radius x its distance to
// the camera (r_max) and r_max / this, drawn with density 1/r^2 (the light's falloff) in between.
SST_CONSTANT float kBrsmInnerRadius = 16.0f;
// Two pVPLs are similar (the filter mixes them) when their normals are closer than this cosine and
// their distance is below r_max: the thesis's S(x, y) (its eq. 5.3).
SST_CONSTANT float kBrsmFilterCos = 0.9f;

// G-buffer pixel (x, y): the first hit of the ray through its centre, the G-buffer covering the
// image of `s.view` at its own resolution.
SST_FUNC BrsmGSample brsm_gbuffer_sample(SCENE_CTX_PARAM RAY_CTX_PARAM SST_IN(BrsmSettings) s, uint x, uint y) {
  BrsmGSample g;
  g.position = vec3(0.0f);
  g.hit = 0.0f;
  g.normal = vec3(0.0f);
  g.pad0 = 0.0f;
  g.albedo = vec3(0.0f);
  g.pad1 = 0.0f;
  SST_PRECISE float px = (float(x) + 0.5f) * float(s.view.width) / float(s.gbuffer_width);
  SST_PRECISE float py = (float(y) + 0.5f) * float(s.view.height) / float(s.gbuffer_height);
  vec3 dir = camera_direction(s.view, px, py);
  BvhHit hit = RAY_INTERSECT(s.view.eye, dir);
  if (hit.triangle >= BVH_STACK_OVERFLOW) return g;  // a miss (or a traversal that gave up)
  Surface surface = make_surface(SCENE_CTX hit.triangle, vec2(hit.u, hit.v), dir);
  g.position = surface.p;
  g.hit = 1.0f;
  g.normal = surface.ns;
  g.albedo = vpl_albedo(surface, s.diffuse_only != 0u);
  return g;
}

// The light a pVPL at p with normal n would send to G-buffer sample g, per unit of its
// luminance, without occlusion; distances below sqrt(floor2) count as that.
SST_FUNC float brsm_light_at(SST_IN(BrsmGSample) g, vec3 p, vec3 n, float floor2) {
  if (!(g.hit > 0.0f)) return 0.0f;
  SST_PRECISE vec3 d = g.position - p;
  SST_PRECISE float d2 = dot3(d, d);
  if (!(d2 > 0.0f)) return 0.0f;
  SST_PRECISE float inv_d = 1.0f / sqrt(d2);
  SST_PRECISE float cos_vpl = dot3(n, d) * inv_d;
  SST_PRECISE float cos_surface = -dot3(g.normal, d) * inv_d;
  if (!(cos_vpl > 0.0f) || !(cos_surface > 0.0f)) return 0.0f;
  SST_PRECISE float light = luminance(g.albedo) * kInvPi * cos_vpl * cos_surface / max(d2, floor2);
  return light;
}

// The expected contribution of a pVPL (position p, normal n, luminance `power`) to what the
// camera sees, without occlusion: `power` times the mean light it would send to
// s.gbuffer_samples G-buffer samples near it (the thesis's 4.1.1, with its sampling around the
// pVPL in 3D) plus the mean over s.screen_samples G-buffer pixels drawn uniformly, which sees the
// pVPLs that light only distant surfaces (0 samples: the thesis's weight).
SST_FUNC float brsm_importance(BRSM_CTX_PARAM SST_IN(BrsmSettings) s, vec3 p, vec3 n, float power,
                               SST_INOUT(HashRng) rng) {
  float to_eye = length3(p - s.view.eye);
  SST_PRECISE float r_max = s.radius * to_eye;
  SST_PRECISE float r_min = r_max / kBrsmInnerRadius;
  SST_PRECISE float floor2 = r_min * r_min;
  float near_sum = 0.0f;
  for (uint k = 0u; k < s.gbuffer_samples; ++k) {
    vec2 u_dir = brsm_next_2d(rng);
    float u_r = hash_rng_next(rng);
    vec3 w = sample_uniform_sphere(u_dir.x, u_dir.y);
    // pdf proportional to 1/r^2 on [r_min, r_max], by inversion of its CDF.
    SST_PRECISE float r = r_min * r_max / (r_max - u_r * (r_max - r_min));
    SST_PRECISE vec3 q = p + w * r;
    vec2 pixel;
    float distance;
    if (!project_to_pixel(s.view, q, pixel, distance)) continue;
    SST_PRECISE float gx = floor(pixel.x * float(s.gbuffer_width) / float(s.view.width));
    SST_PRECISE float gy = floor(pixel.y * float(s.gbuffer_height) / float(s.view.height));
    if (!(gx >= 0.0f && gy >= 0.0f && gx < float(s.gbuffer_width) && gy < float(s.gbuffer_height))) continue;
    SST_PRECISE float summed = near_sum + brsm_light_at(BRSM_GSAMPLE(uint(gy) * s.gbuffer_width + uint(gx)), p, n, floor2);
    near_sum = summed;
  }
  float screen_sum = 0.0f;
  uint pixels = s.gbuffer_width * s.gbuffer_height;
  for (uint k = 0u; k < s.screen_samples; ++k) {
    uint i = min(uint(hash_rng_next(rng) * float(pixels)), pixels - 1u);
    SST_PRECISE float summed = screen_sum + brsm_light_at(BRSM_GSAMPLE(i), p, n, floor2);
    screen_sum = summed;
  }
  if (s.gbuffer_samples == 0u && s.screen_samples == 0u) return power;  // no G-buffer: power alone
  SST_PRECISE float near_mean = s.gbuffer_samples > 0u ? near_sum / float(s.gbuffer_samples) : 0.0f;
  SST_PRECISE float screen_mean = s.screen_samples > 0u ? screen_sum / float(s.screen_samples) : 0.0f;
  SST_PRECISE float weight = power * (near_mean + screen_mean);
  return weight;
}

// Texel `texel` of map `map` (number `map_index`): its light ray's first diffuse hit as a pVPL
// and the pVPL's importance (intensity 0 where the ray escapes or the surface reflects nothing).
SST_FUNC BrsmTexel brsm_texel(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM BRSM_CTX_PARAM SST_IN(BrsmSettings) s,
                              SST_IN(BrsmMap) map, uint map_index, uint texel) {
  BrsmTexel t;
  t.position = vec3(0.0f);
  t.importance = 0.0f;
  t.normal = vec3(0.0f, 0.0f, 1.0f);
  t.pad0 = 0.0f;
  t.intensity = vec3(0.0f);
  t.pad1 = 0.0f;
  HashRng rng = hash_rng(s.seed, texel, map_index, kBrsmTraceStream);
  float u_light = hash_rng_next(rng);
  vec2 u_other = brsm_next_2d(rng);
  vec2 jitter = brsm_next_2d(rng);
  uint res = s.resolution;
  SST_PRECISE vec2 cell = (vec2(float(texel % res), float(texel / res)) + jitter) / float(res);
  cell = min(cell, vec2(kOneMinusEpsilon));
  // A light of the map's range, in proportion to its power.
  SST_PRECISE float u_pick = map.cdf_start + u_light * map.pmf_sum;
  uint index = clamp(light_pick_index(LIGHT_CTX u_pick), map.first_light, map.end_light - 1u);
  float pick = light_pmf(LIGHT_CTX index) / map.pmf_sum;
  if (!(pick > 0.0f)) return t;
  bool directional = index < LIGHT_HEADER.punctual_count && LIGHT_PUNCTUAL(index).type == LIGHT_DIRECTIONAL;
  EmissionFocus focus;
  focus.center = s.focus_center;
  focus.radius = s.focus_radius;
  EmissionSample e;
  e.position = vec3(0.0f);
  e.normal = vec3(0.0f);
  e.direction = vec3(0.0f);
  e.weight = vec3(0.0f);
  e.light = 0u;
  if (!light_emit(SCENE_CTX LIGHT_CTX index, directional ? cell : u_other, directional ? u_other : cell, focus, e))
    return t;
  vec3 origin = e.normal == vec3(0.0f) ? e.position : offset_ray_origin(RAY_EPSILON, e.position, e.normal);
  BvhHit hit = RAY_INTERSECT(origin, e.direction);
  // A traversal that gave up (never on a BVH build_flat_bvh returned) counts as a miss.
  if (hit.triangle >= BVH_STACK_OVERFLOW) return t;
  Surface surface = make_surface(SCENE_CTX hit.triangle, vec2(hit.u, hit.v), e.direction);
  vec3 albedo = vpl_albedo(surface, s.diffuse_only != 0u);
  if (!(dot3(e.direction, surface.ns) < 0.0f) || !(max_component(albedo) > 0.0f)) return t;
  SST_PRECISE vec3 intensity = e.weight * albedo * (kInvPi / (pick * float(res) * float(res)));
  if (!is_finite3(intensity)) return t;
  t.position = surface.p;
  t.normal = surface.ns;
  t.intensity = intensity;
  t.importance = brsm_importance(BRSM_CTX s, surface.p, surface.ns, luminance(intensity), rng);
  return t;
}

// Mip level 0 of texel i: (its importance filtered edge-aware, its luminance). The filter is a
// 5 x 5 binomial kernel over the similar pVPLs (kBrsmFilterCos and r_max), normalised by the
// weights it used; a texel without a pVPL stays (0, 0) so that it is never drawn.
SST_FUNC vec2 brsm_filtered(BRSM_CTX_PARAM SST_IN(BrsmSettings) s, uint i) {
  BrsmTexel t = BRSM_TEXEL(i);
  float power = luminance(t.intensity);
  if (!(power > 0.0f)) return vec2(0.0f);
  if (s.edge_filter == 0u) return vec2(t.importance, power);
  int res = int(s.resolution);
  int x = int(i % s.resolution);
  int y = int(i / s.resolution);
  SST_PRECISE float r_max = s.radius * length3(t.position - s.view.eye);
  SST_PRECISE float r2 = r_max * r_max;
  float sum = 0.0f;
  float weights = 0.0f;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      int nx = x + dx;
      int ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= res || ny >= res) continue;
      BrsmTexel o = BRSM_TEXEL(uint(ny * res + nx));
      if (!(luminance(o.intensity) > 0.0f)) continue;
      SST_PRECISE vec3 d = o.position - t.position;
      if (!(dot3(o.normal, t.normal) > kBrsmFilterCos) || !(dot3(d, d) < r2)) continue;
      // Binomial weights (1 4 6 4 1) per axis: a Gaussian of one texel, exact in floats.
      int ax = 2 - abs(dx);
      int ay = 2 - abs(dy);
      float wx = ax == 2 ? 6.0f : (ax == 1 ? 4.0f : 1.0f);
      float wy = ay == 2 ? 6.0f : (ay == 1 ? 4.0f : 1.0f);
      SST_PRECISE float w = wx * wy;
      SST_PRECISE float summed = sum + w * o.importance;
      sum = summed;
      weights += w;
    }
  }
  SST_PRECISE float filtered = sum / weights;
  return vec2(filtered, power);
}

// Entry `texel` of mip level `level` >= 1: the sum of its four children, in a fixed order.
SST_FUNC vec2 brsm_mip_sum(BRSM_CTX_PARAM uint resolution, uint level, uint texel) {
  uint side = resolution >> level;
  uint child_side = side * 2u;
  uint x = (texel % side) * 2u;
  uint y = (texel / side) * 2u;
  uint base = brsm_mip_offset(resolution, level - 1u);
  SST_PRECISE vec2 top = BRSM_MIP(base + y * child_side + x) + BRSM_MIP(base + y * child_side + x + 1u);
  SST_PRECISE vec2 bottom = BRSM_MIP(base + (y + 1u) * child_side + x) + BRSM_MIP(base + (y + 1u) * child_side + x + 1u);
  SST_PRECISE vec2 sum = top + bottom;
  return sum;
}

// A mip entry's probability mass: (1 - power_fraction) of it by filtered importance and the rest
// by luminance, each as a share of the map's total (`root`); by luminance alone where the map's
// importance is 0 (the camera sees nothing the map lights).
SST_FUNC float brsm_mass(vec2 entry, vec2 root, float power_fraction) {
  if (!(root.y > 0.0f)) return 0.0f;
  if (!(root.x > 0.0f)) return entry.y / root.y;
  SST_PRECISE float mass = (1.0f - power_fraction) * (entry.x / root.x) + power_fraction * (entry.y / root.y);
  return mass;
}

// Splits u at a two-way choice with masses a (taken when u < a / (a + b)) and b, and rescales u to
// [0, 1) within the side taken; returns 0 for a, 1 for b.
SST_FUNC uint brsm_split(float a, float b, SST_INOUT(float) u) {
  SST_PRECISE float total = a + b;
  SST_PRECISE float p = total > 0.0f ? a / total : 0.5f;
  uint side;
  if (u < p) {
    SST_PRECISE float v = u / p;
    u = v;
    side = 0u;
  } else {
    SST_PRECISE float v = (u - p) / (1.0f - p);
    u = v;
    side = 1u;
  }
  u = clamp(u, 0.0f, kOneMinusEpsilon);
  return side;
}

// VPL `point` of the map's `map.vpl_count`: point `point` of a Hammersley set rotated by the map's
// random offset (Cranley-Patterson), warped down the mip chain (at each level a vertical, then a
// horizontal split of the four children by their masses), and the pVPL of the texel it reaches,
// its intensity divided by vpl_count times the texel's probability.
SST_FUNC Vpl brsm_warp(BRSM_CTX_PARAM SST_IN(BrsmSettings) s, SST_IN(BrsmMap) map, uint map_index, uint point) {
  HashRng rng = hash_rng(s.seed, map_index, 0u, kBrsmWarpStream);
  vec2 offset = brsm_next_2d(rng);
  SST_PRECISE float hx = (float(point) + 0.5f) / float(map.vpl_count) + offset.x;
  SST_PRECISE float hy = bits_to_unit_float(bitfieldReverse(point)) + offset.y;
  float ux = hx - floor(hx);
  float uy = hy - floor(hy);
  uint res = s.resolution;
  uint top_level = brsm_top_level(res);
  vec2 root = BRSM_MIP(brsm_mip_offset(res, top_level));
  uint x = 0u;
  uint y = 0u;
  for (uint level = top_level; level > 0u; --level) {
    uint side = res >> (level - 1u);
    uint base = brsm_mip_offset(res, level - 1u);
    uint i00 = base + (2u * y) * side + 2u * x;
    float m00 = brsm_mass(BRSM_MIP(i00), root, s.power_fraction);
    float m10 = brsm_mass(BRSM_MIP(i00 + 1u), root, s.power_fraction);
    float m01 = brsm_mass(BRSM_MIP(i00 + side), root, s.power_fraction);
    float m11 = brsm_mass(BRSM_MIP(i00 + side + 1u), root, s.power_fraction);
    SST_PRECISE float upper = m00 + m10;
    SST_PRECISE float lower = m01 + m11;
    uint row = brsm_split(upper, lower, uy);
    uint col = row == 0u ? brsm_split(m00, m10, ux) : brsm_split(m01, m11, ux);
    x = 2u * x + col;
    y = 2u * y + row;
  }
  uint texel = y * res + x;
  BrsmTexel t = BRSM_TEXEL(texel);
  float probability = brsm_mass(BRSM_MIP(texel), root, s.power_fraction);
  Vpl v;
  v.position = t.position;
  v.normal = t.normal;
  v.intensity = vec3(0.0f);
  if (probability > 0.0f) {
    SST_PRECISE vec3 intensity = t.intensity / (probability * float(map.vpl_count));
    v.intensity = intensity;
  }
  return v;
}

// Element i of stage `stage` (BRSM_STAGE_*; `level`: the mip level BRSM_STAGE_MIP writes) of map
// `map` (number `map_index`), stored through the BRSM_STORE_* hooks; nothing for i beyond
// brsm_stage_size. Both schedules run every element of a stage before the next stage starts.
SST_FUNC void brsm_stage_step(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM BRSM_CTX_PARAM SST_IN(BrsmSettings) s,
                              SST_IN(BrsmMap) map, uint map_index, uint stage, uint level, uint i) {
  if (i >= brsm_stage_size(s, map, stage, level)) return;
  uint res = s.resolution;
  if (stage == BRSM_STAGE_GBUFFER) {
    BRSM_STORE_GSAMPLE(i, brsm_gbuffer_sample(SCENE_CTX RAY_CTX s, i % s.gbuffer_width, i / s.gbuffer_width));
  } else if (stage == BRSM_STAGE_TEXELS) {
    BRSM_STORE_TEXEL(i, brsm_texel(SCENE_CTX LIGHT_CTX RAY_CTX BRSM_CTX s, map, map_index, i));
  } else if (stage == BRSM_STAGE_FILTER) {
    BRSM_STORE_MIP(i, brsm_filtered(BRSM_CTX s, i));
  } else if (stage == BRSM_STAGE_MIP) {
    BRSM_STORE_MIP(brsm_mip_offset(res, level) + i, brsm_mip_sum(BRSM_CTX res, level, i));
  } else if (stage == BRSM_STAGE_WARP) {
    BRSM_STORE_VPL(map.vpl_offset + i, brsm_warp(BRSM_CTX s, map, map_index, i));
  }
}

SST_END

#endif  // SST_CORE_BRSM_BRSM_H
