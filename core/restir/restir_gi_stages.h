// ReSTIR GI's initial reservoirs (Ouyang et al. 2021; shared C++/GLSL source; the passes after them:
// core/restir/restir_stages.h): at each pixel's first hit one BRDF-sampled ray, its hit the
// secondary vertex, and the radiance a path from there brings back toward the first hit (`pt`'s
// path, core/pt/trace_path.h, with next-event estimation at every vertex): the reservoir's one
// candidate. Its emission is left out, as the direct light at the first hit holds it. The
// vertex is visible from its pixel by construction, so no visibility reuse is needed here. And the
// validation of a history's vertex after the scene moved (its pass: core/restir/restir_stages.h).
#ifndef SST_CORE_RESTIR_RESTIR_GI_STAGES_H
#define SST_CORE_RESTIR_RESTIR_GI_STAGES_H
#include "core/pt/trace_path.h"
#include "core/restir/restir_resampling.h"

SST_BEGIN

// The pixel samplers of ReSTIR GI's secondary paths and of its validation paths are seeded apart
// from the camera paths' and from each other.
SST_CONSTANT uint kRestirGiSeed = 0x52474931u;            // "RGI1"
SST_CONSTANT uint kRestirGiValidationSeed = 0x52474956u;  // "RGIV"

// A validation ray starts this fraction of the vertex's distance from its pixel in front of the
// vertex, toward the pixel, and must hit within half of it.
SST_CONSTANT float kRestirGiValidationGap = 0.01f;

// The secondary path's PathConfig: `max_bounces` and `rr_min_bounces` count indirect bounces from
// the pixel, as `pt`'s do; the secondary vertex is the first bounce, so its path has one fewer.
SST_FUNC PathConfig restir_gi_path_config(int max_bounces, int rr_min_bounces, bool diffuse_only) {
  return path_config(max_bounces - 1, max(rr_min_bounces - 1, 0), diffuse_only);
}

// The radiance a secondary path brings back, its vertex's own emission left out. (A helper, as
// product_exact: a precise variable in the path's function would make glslang trace it back
// through the whole path.)
SST_FUNC vec3 restir_gi_radiance(vec3 direct, vec3 emission, vec3 indirect) {
  SST_PRECISE vec3 r = direct - emission + indirect;
  return r;
}

// The resampling weight of a candidate of target `target` drawn with solid-angle density `pdf`,
// `g` converting it to a density per unit area.
SST_FUNC float restir_gi_weight(float target, float pdf, float g) {
  SST_PRECISE float density = pdf * g;
  SST_PRECISE float w = target / density;
  return w;
}

// Surface s's initial reservoir: M = 1, its candidate (if any) with W = 1 / its density per unit
// area of the secondary surface. `ps` draws the BRDF sample and the path.
SST_FUNC RestirReservoir restir_gi_initial(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirSurface) s,
                                           bool diffuse_only, int max_bounces, int rr_min_bounces,
                                           SST_INOUT(PixelSampler) ps, SST_INOUT(PathCounters) counters) {
  RestirReservoir r = restir_reservoir_empty();
  if (s.hit == 0u) return r;
  r.m = 1.0f;
  vec2 u = pixel_sampler_get2d(ps);
  Basis basis;
  vec3 wo;
  if (max_bounces < 1 || !shading_frame(s.ns, s.ng, s.dir, basis, wo)) return r;
  Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, diffuse_only);
  BrdfSample bs;
  if (!brdf_sample(brdf, wo, u, bs)) return r;
  vec3 wi = to_world(basis, bs.wi);
  if (dot3(wi, s.ng) <= 0.0f) return r;  // would pass through the surface
  PathState st = path_begin(offset_ray_origin(s.offset, s.p, s.ng), wi, ps);
  trace_path_state(SCENE_CTX LIGHT_CTX RAY_CTX st, restir_gi_path_config(max_bounces, rr_min_bounces, diffuse_only));
  ps = st.ps;
  counters.bounce_rays += st.counters.primary_rays + st.counters.bounce_rays;
  counters.shadow_rays += st.counters.shadow_rays;
  if (!st.hit) return r;  // the world is black
  vec3 radiance = restir_gi_radiance(st.result.direct, st.first_hit.emission, st.result.indirect);
  RestirReservoir candidate = r;
  candidate.light = RESTIR_GI_VERTEX;
  candidate.point = st.first_hit.p;
  candidate.normal = st.first_hit.ng;  // turned toward the ray: the side the radiance leaves from
  candidate.offset = st.first_hit.offset;
  candidate.radiance = radiance;
  candidate.triangle = st.first_hit.triangle;
  vec3 v0;
  vec3 v1;
  vec3 v2;
  light_triangle_vertices(SCENE_CTX candidate.triangle, v0, v1, v2);
  vec2 b = barycentric_of(v0, v1, v2, candidate.point);
  candidate.b1 = b.x;
  candidate.b2 = b.y;
  ShadowRay ray;
  LightSample ls;
  float g;
  float target = luminance(restir_contribution(SCENE_CTX LIGHT_CTX s, diffuse_only, candidate, ray, ls, g));
  float w = restir_gi_weight(target, bs.pdf, g);
  float weight_sum = 0.0f;
  if (!reservoir_accept(weight_sum, w, 0.0f)) return r;
  candidate.target = target;
  candidate.weight = reservoir_contribution_weight(weight_sum, 1.0f, target);
  return candidate;
}

// Validation, the paper's answer to stale samples: after the scene moved (an animation, a moving
// light), reservoir r of the history's pixel whose first hit was sh gets its vertex back from its
// triangle and barycentrics as posed now, and the radiance a new path from there brings back toward
// sh; its W and M stay (restir_temporal then evaluates its target anew). The path's first ray
// starts a little in front of the vertex, toward sh, and must find it there: where something now
// covers the vertex the reservoir is dropped (empty, M = 0).
SST_FUNC RestirReservoir restir_gi_validate(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirSurface) sh,
                                            SST_IN(RestirReservoir) r, bool diffuse_only, int max_bounces,
                                            int rr_min_bounces, SST_INOUT(PixelSampler) ps,
                                            SST_INOUT(PathCounters) counters) {
  if (r.light != RESTIR_GI_VERTEX || sh.hit == 0u) return r;
  vec3 v0;
  vec3 v1;
  vec3 v2;
  light_triangle_vertices(SCENE_CTX r.triangle, v0, v1, v2);
  vec3 y = barycentric_mix3(v0, v1, v2, vec2(r.b1, r.b2));
  SST_PRECISE vec3 to_pixel = sh.p - y;
  float distance = length3(to_pixel);
  if (!(distance > 0.0f)) return restir_reservoir_empty();
  SST_PRECISE vec3 toward = to_pixel / distance;
  SST_PRECISE float gap = kRestirGiValidationGap * distance;
  SST_PRECISE vec3 origin = y + toward * gap;
  PathState st = path_begin(origin, -toward, ps);
  trace_path_state(SCENE_CTX LIGHT_CTX RAY_CTX st, restir_gi_path_config(max_bounces, rr_min_bounces, diffuse_only));
  ps = st.ps;
  counters.bounce_rays += st.counters.primary_rays + st.counters.bounce_rays;
  counters.shadow_rays += st.counters.shadow_rays;
  if (!st.hit || !(length3(st.first_hit.p - y) <= 0.5f * gap)) return restir_reservoir_empty();
  RestirReservoir v = r;
  v.point = st.first_hit.p;
  v.normal = st.first_hit.ng;
  v.offset = st.first_hit.offset;
  v.radiance = restir_gi_radiance(st.result.direct, st.first_hit.emission, st.result.indirect);
  return v;
}

// Pixel (x, y)'s initial pass for the round of `push`: its camera ray's first hit (into `s`) and
// its initial reservoir.
SST_FUNC RestirReservoir restir_gi_initial_pixel(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirPush) push,
                                                 uint x, uint y, SST_OUT(RestirSurface) s,
                                                 SST_INOUT(PathCounters) counters) {
  uint round = push.view.sample_offset;
  s = restir_camera(SCENE_CTX RAY_CTX push.view, x, y, round, counters);
  PixelSampler ps = pixel_sampler(push.view.seed ^ kRestirGiSeed, y * push.view.width + x, round);
  return restir_gi_initial(SCENE_CTX LIGHT_CTX RAY_CTX s, (push.flags & RESTIR_DIFFUSE_ONLY) != 0u, push.max_bounces,
                           push.rr_min_bounces, ps, counters);
}

SST_END

#endif  // SST_CORE_RESTIR_RESTIR_GI_STAGES_H
