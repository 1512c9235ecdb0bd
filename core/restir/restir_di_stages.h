// ReSTIR DI's initial reservoirs (shared C++/GLSL source; the passes after them:
// core/restir/restir_stages.h): RIS over `light_candidates` light samples (--light-sampler) and
// `brdf_candidates` BRDF rays that hit an emitter, combined by the balance heuristic, then
// visibility reuse (the kept sample's shadow ray; W = 0 when occluded).
#ifndef SST_CORE_RESTIR_RESTIR_DI_STAGES_H
#define SST_CORE_RESTIR_RESTIR_DI_STAGES_H
#include "core/restir/restir_resampling.h"

SST_BEGIN

// One candidate streamed into the initial reservoir: the sample (light, b) at s, drawn by a
// strategy of the mixture whose density per unit area at it is m_light p_light + m_brdf p_brdf
// (p_light_solid_angle: light sampling's density there; < 0 to compute it).
SST_FUNC void restir_stream_candidate(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_IN(RestirSurface) s, bool diffuse_only,
                                      uint light, vec2 b, float p_light_solid_angle, float m_light, float m_brdf,
                                      float u, SST_INOUT(RestirReservoir) r, SST_INOUT(float) weight_sum) {
  RestirReservoir candidate = restir_reservoir_empty();
  candidate.light = light;
  candidate.b1 = b.x;
  candidate.b2 = b.y;
  ShadowRay ray;
  LightSample ls;
  float g;
  float target = luminance(restir_contribution(SCENE_CTX LIGHT_CTX s, diffuse_only, candidate, ray, ls, g));
  if (!(target > 0.0f)) return;
  Basis basis;
  vec3 wo;
  shading_frame(s.ns, s.ng, s.dir, basis, wo);
  float p_light = p_light_solid_angle;
  if (p_light < 0.0f) {
    uint tri = LIGHT_EMISSIVE(light - LIGHT_HEADER.punctual_count).triangle;
    p_light = light_pdf_emissive_hit(SCENE_CTX LIGHT_CTX s.p, s.ns, tri, ls.point, ls.normal);
  }
  float p_brdf = 0.0f;
  if (!ls.delta) {
    Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, diffuse_only);
    p_brdf = brdf_pdf(brdf, wo, to_local(basis, ls.wi));
  }
  SST_PRECISE float density = (m_light * p_light + m_brdf * p_brdf) * g;
  SST_PRECISE float w = target / density;
  if (reservoir_accept(weight_sum, w, u)) {
    r = candidate;
    r.target = target;
  }
}

// RIS at surface s over `light_candidates` light samples and `brdf_candidates` (0 or 1) BRDF
// rays, each weighted by the balance heuristic over both strategies, then visibility reuse.
SST_FUNC RestirReservoir restir_di_initial(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirSurface) s,
                                       bool diffuse_only, uint light_candidates, uint brdf_candidates,
                                       SST_INOUT(HashRng) rng, SST_INOUT(PathCounters) counters) {
  RestirReservoir r = restir_reservoir_empty();
  if (s.hit == 0u) return r;
  float m_light = float(light_candidates);
  float m_brdf = float(brdf_candidates);
  float weight_sum = 0.0f;
  for (uint i = 0u; i < light_candidates; ++i) {
    vec2 u = restir_next2(rng);
    float u_accept = hash_rng_next(rng);
    LightSample cand;
    uint light;
    vec2 b;
    if (!light_sample_at(SCENE_CTX LIGHT_CTX s.p, s.ns, u, cand, light, b)) continue;
    restir_stream_candidate(SCENE_CTX LIGHT_CTX s, diffuse_only, light, b, cand.pdf, m_light, m_brdf, u_accept, r,
                            weight_sum);
  }
  Basis basis;
  vec3 wo;
  if (brdf_candidates > 0u && shading_frame(s.ns, s.ng, s.dir, basis, wo)) {
    vec2 u = restir_next2(rng);
    float u_accept = hash_rng_next(rng);
    Brdf brdf = brdf_from_material(s.base_color, s.metallic, s.roughness, diffuse_only);
    BrdfSample bs;
    if (brdf_sample(brdf, wo, u, bs)) {
      vec3 wi = to_world(basis, bs.wi);
      if (dot3(wi, s.ng) > 0.0f) {
        counters.bounce_rays += 1u;
        BvhHit h = RAY_INTERSECT(offset_ray_origin(s.offset, s.p, s.ng), wi);
        uint light = h.triangle < LIGHT_HEADER.triangle_count ? LIGHT_OF_TRIANGLE(h.triangle) : LIGHT_NONE;
        if (light != LIGHT_NONE)
          restir_stream_candidate(SCENE_CTX LIGHT_CTX s, diffuse_only, light, vec2(h.u, h.v), -1.0f, m_light, m_brdf,
                                  u_accept, r, weight_sum);
      }
    }
  }
  r.m = m_light + m_brdf;
  r.weight = reservoir_contribution_weight(weight_sum, 1.0f, r.target);
  restir_visibility_reuse(SCENE_CTX LIGHT_CTX RAY_CTX s, diffuse_only, r, counters);
  return r;
}

// Pixel (x, y)'s initial pass for the round of `push`: its camera ray's first hit (into `s`) and
// its initial reservoir.
SST_FUNC RestirReservoir restir_di_initial_pixel(SCENE_CTX_PARAM LIGHT_CTX_PARAM RAY_CTX_PARAM SST_IN(RestirPush) push,
                                                 uint x, uint y, SST_OUT(RestirSurface) s,
                                                 SST_INOUT(PathCounters) counters) {
  uint round = push.view.sample_offset;
  s = restir_camera(SCENE_CTX RAY_CTX push.view, x, y, round, counters);
  HashRng rng = hash_rng(push.view.seed, y * push.view.width + x, round, kRestirStreamInitial);
  return restir_di_initial(SCENE_CTX LIGHT_CTX RAY_CTX s, (push.flags & RESTIR_DIFFUSE_ONLY) != 0u,
                           push.light_candidates, push.brdf_candidates, rng, counters);
}

SST_END

#endif  // SST_CORE_RESTIR_RESTIR_DI_STAGES_H
