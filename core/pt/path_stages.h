// The stages of one camera path of `pt` (shared C++/GLSL source), between its ray queries: a path
// is a PathState that each stage advances up to its next ray, so that the rays can be traced one
// at a time (trace_path, core/pt/trace_path.h: a path to its end, the GPU megakernel) or for a
// batch of paths together (core/pt/path_batch.h: Embree ray streams on the CPU; the wavefront
// kernels of gpu/shaders/pt_wavefront.comp). One path's stages run in the same order however its
// rays are traced, so it draws the same random numbers and adds the same floats: every schedule
// gives the same image bits.
//
// A path's rays, in order: the camera ray, then at each vertex a shadow ray (next-event
// estimation, MIS by the power heuristic against BRDF sampling) and a bounce ray (whose hit adds
// the emission it sees, MIS-weighted), Russian roulette after rr_min_bounces.
//
//   path_begin            the camera ray                        -> PATH_RAY_BOUNCE (the camera ray)
//   path_first_hit        its hit: first_hit, albedo, emission  -> PATH_ACTIVE or done
//   path_shade            a vertex: light and BRDF samples      -> PATH_RAY_SHADOW, PATH_RAY_BOUNCE
//   path_shadow_result    the shadow ray's answer: the light sample's share is added
//   path_bounce_hit       the bounce ray's hit: emission, roulette -> PATH_ACTIVE or done
//
// The stages use the scene's hooks (core/shading/surface_eval.h) and the lights'
// (core/lights/light_sample.h), never the ray queries: the schedule traces the rays the state
// asks for (PathState.flags) and hands each stage the answer.
#ifndef SST_CORE_PT_PATH_STAGES_H
#define SST_CORE_PT_PATH_STAGES_H
#include "core/accel/bvh_layout.h"
#include "core/accel/ray_offset.h"
#include "core/material/brdf.h"
#include "core/render/frame_layout.h"
#include "core/rng/sobol_sampler.h"
#include "core/sampling/sampling.h"
#include "core/vpl/vpl_shading.h"

SST_BEGIN

// One camera path's contribution, split the way the EXR layers are.
struct PathSample {
  vec3 direct SST_DEFAULT(vec3(0.0f));    // emission seen + direct light at the first hit
  vec3 indirect SST_DEFAULT(vec3(0.0f));  // everything after the first bounce
  vec3 albedo SST_DEFAULT(vec3(0.0f));    // base colour at the first hit
  vec3 normal SST_DEFAULT(vec3(0.0f));    // shading normal at the first hit
  float depth SST_DEFAULT(0.0f);          // distance to the first hit; 0 for a miss
};

// The rays a path traced.
struct PathCounters {
  uint primary_rays SST_DEFAULT(0u);
  uint shadow_rays SST_DEFAULT(0u);
  uint bounce_rays SST_DEFAULT(0u);
};

SST_FUNC PathCounters path_counters() {
  PathCounters c;
  c.primary_rays = 0u;
  c.shadow_rays = 0u;
  c.bounce_rays = 0u;
  return c;
}

// A path's settings: PathTracerParams and RenderOptions::diffuse_only. max_bounces -1: the first
// hit and its emission only, for a method that samples the direct light itself; 0: direct light.
//
// The VPL methods' direct pass may also compensate their singularity clamp (core/manylight/
// direct_pass.h): with clamp_distance or clamp_per_depth > 0 the path continues past its first
// bounce only where that bounce lands closer than the clamp c = vpl_clamp_at(clamp_distance,
// clamp_per_depth, depth of the first hit), its throughput weighted by 1 - d^2/c^2: the part of
// the light from surfaces within c that the clamped VPL estimate leaves out (Kollig and Keller
// 2004). What it gathers from vertex 2 on goes to the indirect layer.
struct PathConfig {
  int max_bounces;
  int rr_min_bounces;
  bool diffuse_only;
  bool first_vertex_light;  // false: vertex 1 gathers no light (a method with its own direct light)
  float clamp_distance;
  float clamp_per_depth;
};

SST_FUNC PathConfig path_config(int max_bounces, int rr_min_bounces, bool diffuse_only) {
  PathConfig c;
  c.max_bounces = max_bounces;
  c.rr_min_bounces = rr_min_bounces;
  c.diffuse_only = diffuse_only;
  c.first_vertex_light = true;
  c.clamp_distance = 0.0f;
  c.clamp_per_depth = 0.0f;
  return c;
}

// c with vertex 1 gathering no light: the first hit's direct light is estimated elsewhere (ReSTIR
// DI, core/restir/restir_di_stages.h), the emission the camera sees stays the path's. A path that
// would end at vertex 1 (max_bounces 0) ends at its first hit, tracing no ray for light it would
// not gather.
SST_FUNC PathConfig path_direct_elsewhere(PathConfig c) {
  if (c.max_bounces == 0) c.max_bounces = -1;
  else c.first_vertex_light = false;
  return c;
}

// `pt`'s path for RenderOptions' path flags (RENDER_*, core/render/frame_layout.h).
SST_FUNC PathConfig path_config_for(int max_bounces, int rr_min_bounces, uint render_flags) {
  PathConfig c = path_config(max_bounces, rr_min_bounces, (render_flags & RENDER_DIFFUSE_ONLY) != 0u);
  return (render_flags & RENDER_RESTIR_DIRECT) != 0u ? path_direct_elsewhere(c) : c;
}

SST_FUNC bool path_compensates_clamp(SST_IN(PathConfig) cfg) {
  return cfg.clamp_distance > 0.0f || cfg.clamp_per_depth > 0.0f;
}

// A shadow ray: whether anything lies on origin + t dir, t in [0, tmax).
struct ShadowRay {
  vec3 origin;
  float tmax;
  vec3 dir;
};

// PathState.flags: what the path waits for.
SST_CONSTANT uint PATH_ACTIVE = 1u;      // a vertex to shade (path_shade)
SST_CONSTANT uint PATH_RAY_SHADOW = 2u;  // `shadow` to trace, then path_shadow_result
SST_CONSTANT uint PATH_NEE = 4u;         // path_shadow_result adds `nee` (with or without a shadow ray)
SST_CONSTANT uint PATH_RAY_BOUNCE = 8u;  // origin + t dir to intersect, then path_first_hit (k = 0) or path_bounce_hit

// Everything a path carries from one stage to the next.
struct PathState {
  PathSample result;
  PathCounters counters;
  PixelSampler ps;
  Surface s;          // the vertex being shaded
  Surface first_hit;  // what the camera ray hit (Surface's defaults before, or after a miss)
  vec3 origin;        // the ray to intersect: the camera ray, then each bounce
  vec3 dir;
  vec3 beta;           // throughput from the camera to s
  vec3 nee;            // the light sample's share at s, before its shadow ray; zero when none
  ShadowRay shadow;
  vec3 bounce_weight;  // the BRDF sample's f cos / pdf, its pdf, and the roulette's number
  float bounce_pdf;
  float u_roulette;
  int k;               // s is vertex k (1: the first hit); 0 before the camera ray's hit
  uint flags;
  bool hit;            // the camera ray hit something
};

// Where the shadow-terminator lift (Surface.lift) starts to move shadow rays: the cosine of the
// light with either normal below which they leave from the lifted point, as Cycles' default
// shadow_terminator_geometry_offset (0.1).
SST_CONSTANT float kTerminatorCosine = 0.1f;

// Light sample ls seen from p (geometric normal ng, terminator lift `lift`, ray lift `offset`)
// through the BRDF, before visibility: weighted by the power heuristic against BRDF sampling when
// `mis`, else the only estimate of that light's contribution. Zero, with no ray to trace
// (`needs_ray` false), when the light cannot contribute.
SST_FUNC vec3 light_sample_unshadowed(vec3 p, vec3 ng, vec3 lift, float offset, SST_IN(Brdf) brdf, SST_IN(Basis) basis,
                                      vec3 wo, SST_IN(LightSample) ls, bool mis, SST_OUT(ShadowRay) ray,
                                      SST_OUT(bool) needs_ray) {
  ray.origin = p;
  ray.dir = ls.wi;
  ray.tmax = 0.0f;
  needs_ray = false;
  // Light from behind the geometric surface would leak through it: nothing is transmitted. But on a
  // smooth-shaded mesh (lift not zero) light under the facet may still reach the smooth surface
  // the shading normal describes: its shadow ray, from the lifted point, decides.
  float ngl = dot3(ls.wi, ng);
  if (ngl <= 0.0f && dot3(lift, lift) == 0.0f) return vec3(0.0f);
  vec3 wi = to_local(basis, ls.wi);
  vec3 f = brdf_eval(brdf, wo, wi);
  if (wi.z <= 0.0f || max_component(f) <= 0.0f || max_component(ls.li) <= 0.0f) return vec3(0.0f);
  // Near the shadow terminator of a smooth-shaded mesh the ray leaves from the lifted point, blended
  // in as Cycles does: fully where either cosine is 0, not at all where both exceed the cutoff.
  float nl = wi.z;
  float amount = nl < kTerminatorCosine ? clamp(2.0f - (ngl + nl) / kTerminatorCosine, 0.0f, 1.0f)
                                        : clamp(1.0f - ngl / kTerminatorCosine, 0.0f, 1.0f);
  SST_PRECISE vec3 from = amount > 0.0f ? p + lift * amount : p;
  if (isinf(ls.distance)) {
    ray.origin = offset_ray_origin(offset, from, ng);
    ray.dir = ls.wi;
    ray.tmax = kInf;
  } else {
    shadow_ray_segment(offset, from, ng, ls.offset, ls.point, ls.normal, ray.origin, ray.dir, ray.tmax);
  }
  needs_ray = true;
  float weight = ls.delta || !mis ? 1.0f : power_heuristic(ls.pdf, brdf_pdf(brdf, wo, wi));
  SST_PRECISE vec3 r = f * wi.z * ls.li * (weight / ls.pdf);
  return r;
}

// a * b, never contracted into the addition it feeds. A helper rather than precise variables in
// the stages: glslang traces a precise variable back through every call argument and
// loop-carried value that feeds it, which in a path's loop took it minutes and gigabytes (and
// whether it did changed with unrelated edits); here the trace ends at the parameters.
SST_FUNC vec3 product_exact(vec3 a, vec3 b) {
  SST_PRECISE vec3 r = a * b;
  return r;
}

// The frame a vertex is shaded in, seen along `dir` (the ray that found it): the shading normal
// ns's, or the facet's (ng) where the view lies under ns but above the facet (a coarse curved mesh
// at a grazing angle; ending the path there lost the light such surfaces reflect, darkening what
// they light: results/README.md, thin tubes against Cycles). `wo` is the view in that frame.
// False exactly at grazing on the facet: no reflection is defined.
SST_FUNC bool shading_frame(vec3 ns, vec3 ng, vec3 dir, SST_OUT(Basis) basis, SST_OUT(vec3) wo) {
  basis = basis_from_normal(ns);
  wo = to_local(basis, -normalize3(dir));
  if (wo.z <= 0.0f) {
    basis = basis_from_normal(ng);
    wo = to_local(basis, -normalize3(dir));
  }
  return wo.z > 0.0f;
}

// What first_hit holds after a miss: Surface's defaults.
SST_FUNC Surface surface_none() {
  Surface s;
  s.p = vec3(0.0f);
  s.ng = vec3(0.0f);
  s.ns = vec3(0.0f);
  s.uv = vec2(0.0f);
  s.triangle = 0u;
  s.material = 0u;
  s.front_face = true;
  s.base_color = vec3(1.0f);
  s.metallic = 0.0f;
  s.roughness = 1.0f;
  s.emission = vec3(0.0f);
  s.offset = 0.0f;
  s.lift = vec3(0.0f);
  return s;
}

// A path starting with the camera ray origin + t dir; `ps` has drawn the pixel jitter.
SST_FUNC PathState path_begin(vec3 origin, vec3 dir, SST_IN(PixelSampler) ps) {
  PathState st;
  st.result.direct = vec3(0.0f);
  st.result.indirect = vec3(0.0f);
  st.result.albedo = vec3(0.0f);
  st.result.normal = vec3(0.0f);
  st.result.depth = 0.0f;
  st.counters = path_counters();
  st.counters.primary_rays = 1u;
  st.ps = ps;
  st.s = surface_none();
  st.first_hit = surface_none();
  st.origin = origin;
  st.dir = dir;
  st.beta = vec3(1.0f);
  st.nee = vec3(0.0f);
  st.shadow.origin = origin;
  st.shadow.dir = dir;
  st.shadow.tmax = 0.0f;
  st.bounce_weight = vec3(0.0f);
  st.bounce_pdf = 0.0f;
  st.u_roulette = 0.0f;
  st.k = 0;
  st.flags = PATH_RAY_BOUNCE;
  st.hit = false;
  return st;
}

// The camera ray's hit h on surface s.
SST_FUNC void path_first_surface(SST_INOUT(PathState) st, BvhHit h, SST_IN(Surface) s, SST_IN(PathConfig) cfg) {
  st.s = s;
  st.first_hit = s;
  st.hit = true;
  st.result.albedo = s.base_color;
  st.result.normal = s.ns;
  st.result.depth = h.t * length3(st.dir);
  st.result.direct = s.emission;
  // Vertex k = 1 is the first hit. Light arriving at vertex k has made k-1 indirect bounces, so
  // vertices 1 .. max_bounces+1 gather light, and vertex 1's share is the direct layer.
  st.k = 1;
  if (st.k <= cfg.max_bounces + 1) st.flags = PATH_ACTIVE;
}

// The camera ray's hit h (triangle >= BVH_STACK_OVERFLOW: a miss, and the path ends).
SST_FUNC void path_first_hit(SCENE_CTX_PARAM SST_INOUT(PathState) st, BvhHit h, SST_IN(PathConfig) cfg) {
  st.flags = 0u;
  if (h.triangle >= BVH_STACK_OVERFLOW) return;
  path_first_surface(st, h, make_surface(SCENE_CTX h.triangle, vec2(h.u, h.v), st.dir), cfg);
}

// Vertex st.s: its light sample (PATH_NEE, and PATH_RAY_SHADOW when visibility decides it) and its
// BRDF sample (PATH_RAY_BOUNCE) unless the path ends here.
SST_FUNC void path_shade(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_INOUT(PathState) st, SST_IN(PathConfig) cfg) {
  st.flags = 0u;
  Brdf brdf = brdf_from_material(st.s.base_color, st.s.metallic, st.s.roughness, cfg.diffuse_only);
  Basis basis;
  vec3 wo;
  if (!shading_frame(st.s.ns, st.s.ng, st.dir, basis, wo)) return;

  // Every vertex draws its samples in the same order (light, BRDF, roulette), so sample set
  // numbers line up across paths and the sets stay stratified per vertex.
  vec2 u_light = pixel_sampler_get2d(st.ps);
  vec2 u_brdf = pixel_sampler_get2d(st.ps);
  st.u_roulette = pixel_sampler_get1d(st.ps);
  st.flags = PATH_NEE;
  st.nee = vec3(0.0f);
  LightSample ls;
  if ((st.k > 1 || cfg.first_vertex_light) && light_sample(SCENE_CTX LIGHT_CTX st.s.p, st.s.ns, u_light, ls)) {
    bool needs_ray;
    st.nee = light_sample_unshadowed(st.s.p, st.s.ng, st.s.lift, st.s.offset, brdf, basis, wo, ls, true, st.shadow,
                                     needs_ray);
    if (needs_ray) {
      st.flags |= PATH_RAY_SHADOW;
      st.counters.shadow_rays += 1u;
    }
  }
  // The last vertex's bounce ray only looks for emission (the MIS half of its direct light): in a
  // scene where no triangle emits (LightHeader.emissive_count) it would find none. It cost the
  // many-light methods' direct pass (max_bounces 0) a third of its rays.
  if (st.k == cfg.max_bounces + 1 && LIGHT_HEADER.emissive_count == 0u) return;

  BrdfSample bs;
  if (!brdf_sample(brdf, wo, u_brdf, bs)) return;
  vec3 wi = to_world(basis, bs.wi);
  if (dot3(wi, st.s.ng) <= 0.0f) return;  // would pass through the surface
  st.origin = offset_ray_origin(st.s.offset, st.s.p, st.s.ng);
  st.dir = wi;
  st.bounce_weight = bs.weight;
  st.bounce_pdf = bs.pdf;
  st.counters.bounce_rays += 1u;
  st.flags |= PATH_RAY_BOUNCE;
}

// The answer to the shadow ray of path_shade (false when it asked for none): the light sample's
// share is added to the direct layer at the first hit, to the indirect one after.
SST_FUNC void path_shadow_result(SST_INOUT(PathState) st, bool occluded) {
  if ((st.flags & PATH_NEE) == 0u) return;
  vec3 direct = product_exact(st.beta, occluded ? vec3(0.0f) : st.nee);
  if (st.k == 1) st.result.direct += direct;
  else st.result.indirect += direct;
  st.flags &= ~(PATH_NEE | PATH_RAY_SHADOW);
}

// The bounce ray's hit `next` on surface ns: the emission it sees, MIS-weighted against the light
// sampler, then Russian roulette; ns becomes the vertex to shade while vertices remain.
SST_FUNC void path_bounce_surface(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_INOUT(PathState) st, BvhHit next,
                                  SST_IN(Surface) ns, SST_IN(PathConfig) cfg) {
  vec3 beta_next = st.beta * st.bounce_weight;
  if (max_component(ns.emission) > 0.0f && (st.k > 1 || cfg.first_vertex_light)) {
    float light_pdf = light_pdf_emissive_hit(SCENE_CTX LIGHT_CTX st.s.p, st.s.ns, next.triangle, ns.p, ns.ng);
    vec3 emitted = product_exact(beta_next * ns.emission, vec3(power_heuristic(st.bounce_pdf, light_pdf)));
    if (st.k == 1) st.result.direct += emitted;
    else st.result.indirect += emitted;
  }
  if (st.k == 1 && path_compensates_clamp(cfg)) {
    float c = vpl_clamp_at(cfg.clamp_distance, cfg.clamp_per_depth, st.result.depth);
    float residual = vpl_clamp_residual(st.s.p, ns.p, c);
    if (!(residual > 0.0f)) return;  // the clamped VPL estimate holds all of this light
    beta_next = product_exact(beta_next, vec3(residual));
  }
  st.beta = beta_next;
  st.s = ns;

  // Russian roulette after rr_min_bounces indirect bounces; k-1 have been made to reach s.
  // (k > rr_min_bounces, not k >= rr_min_bounces + 1, which overflows at INT_MAX.)
  if (st.k > cfg.rr_min_bounces && st.k <= cfg.max_bounces) {
    float survive = min(1.0f, max_component(st.beta));
    if (st.u_roulette >= survive) return;
    st.beta = st.beta / survive;
  }
  st.k += 1;
  if (st.k <= cfg.max_bounces + 1) st.flags = PATH_ACTIVE;
}

// The bounce ray's hit `next` (a miss ends the path: the world is black).
SST_FUNC void path_bounce_hit(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_INOUT(PathState) st, BvhHit next,
                              SST_IN(PathConfig) cfg) {
  st.flags = 0u;
  if (next.triangle >= BVH_STACK_OVERFLOW) return;
  path_bounce_surface(SCENE_CTX LIGHT_CTX st, next, make_surface(SCENE_CTX next.triangle, vec2(next.u, next.v), st.dir),
                      cfg);
}

// path_first_hit for the camera ray (k = 0), path_bounce_hit after: one closest-hit site for a
// whole path, so that a shader inlines the surface's evaluation (its textures) once.
SST_FUNC void path_hit(SCENE_CTX_PARAM LIGHT_CTX_PARAM SST_INOUT(PathState) st, BvhHit h, SST_IN(PathConfig) cfg) {
  st.flags = 0u;
  if (h.triangle >= BVH_STACK_OVERFLOW) return;
  Surface s = make_surface(SCENE_CTX h.triangle, vec2(h.u, h.v), st.dir);
  if (st.k == 0) path_first_surface(st, h, s, cfg);
  else path_bounce_surface(SCENE_CTX LIGHT_CTX st, h, s, cfg);
}

SST_END

#endif  // SST_CORE_PT_PATH_STAGES_H
