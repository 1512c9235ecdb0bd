// What every reservoir resampling in sst is built from (shared C++/GLSL source, no buffers):
// a reservoir's sample seen from a surface (a light's point or a GI vertex, restir_sample_at), its
// target function and visibility, visibility reuse, merging reservoirs by pairwise MIS
// (restir_merge_*), the similarity test of two surfaces and the shading of the kept sample.
// ReSTIR's image passes (core/restir/restir_stages.h) and GI-1.0's reservoirs at its cache points
// (core/gi10/gi10_cache.h) both use them; core/restir/restir_stages.h says what a sample is and
// in which measure the target is taken.
//
// Hooks: the scene's (core/shading/surface_eval.h), the lights' (core/lights/light_sample.h) and
// the ray queries (core/pt/trace_path.h lists them).
#ifndef SST_CORE_RESTIR_RESTIR_RESAMPLING_H
#define SST_CORE_RESTIR_RESTIR_RESAMPLING_H
#include "core/accel/bvh_layout.h"
#include "core/math/accurate_math.h"
#include "core/math/geometric_similarity.h"
#include "core/pt/path_stages.h"
#include "core/render/pinhole.h"
#include "core/restir/reservoir.h"
#include "core/restir/restir_layout.h"
#include "core/rng/hash_rng.h"

#if !defined(RAY_CTX_PARAM) || !defined(RAY_CTX) || !defined(RAY_INTERSECT) || !defined(RAY_OCCLUDED)
#error "define the RAY_* hooks before including core/restir/restir_resampling.h"
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
  r.triangle = 0u;
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

SST_END

#endif  // SST_CORE_RESTIR_RESTIR_RESAMPLING_H
