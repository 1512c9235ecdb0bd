// Light sampling over every light of a scene, in the common subset of C++ and GLSL
// (core/math/cpu_gpu.h): LightSampler (core/lights/light_sampler.h) on the CPU, the shaders on
// the GPU. One light is picked by the header's sampler (LIGHT_SAMPLER_*: uniformly, in proportion
// to its power from the distribution's CDF, or for the shading point down the emitter tree,
// core/lights/emitter_tree.h), then a point on it (punctual lights: their position or direction;
// emissive triangles: uniform by solid angle where the triangle subtends a large angle from the
// shading point, uniform by area otherwise); also the pdf of hitting an emissive triangle by BSDF sampling (for MIS) and the
// start of a light path (sample_emission, for VPLs). What each returns is documented at
// LightSampler.
//
// The tables are core/lights/light_layout.h's, read through hooks the includer defines before
// including this file, besides the SCENE_* hooks of core/shading/surface_eval.h:
//   LIGHT_CTX_PARAM       a leading parameter with its trailing comma through which the hooks
//                         reach the tables (C++: `const ::sst::PackedLights& lights,`), empty in
//                         GLSL
//   LIGHT_CTX             the same as an argument
//   LIGHT_HEADER          LightHeader: the counts and the scene bounds
//   LIGHT_PUNCTUAL(i)     LightPunctual: punctual light i (distribution entry i)
//   LIGHT_CDF(i)          LightCdfEntry: entry i of the distribution over all lights
//   LIGHT_EMISSIVE(k)     LightEmissive: emissive triangle k (distribution entry punctual_count + k)
//   LIGHT_OF_TRIANGLE(t)  uint: the distribution entry of scene triangle t, or LIGHT_NONE
//   LIGHT_TREE(i)         EmitterNode: node i of the emitter tree (tree and slc samplers)
// and, optionally, LIGHT_SAMPLER_KIND: the sampler (LIGHT_SAMPLER_*), LIGHT_HEADER.sampler_kind
// unless the includer fixes it (a GPU pipeline's specialization constant,
// gpu/shaders/specialization.glsl, so that the driver compiles one sampler, not four).
//
// The distribution's CDF was summed in double; each entry holds it as a hi/lo float pair. The pick
// compares `cdf > u` exactly through the pair, so the light picked for a float u is the one a
// double CDF picks; the remapped u is computed in float-float arithmetic (~48 bits) and rounded
// once. Spherical (solid-angle) samples and emission directions go through
// core/math/accurate_math.h's asin/atan2/sin/cos, which both backends compute alike.
#ifndef SST_CORE_LIGHTS_LIGHT_SAMPLE_H
#define SST_CORE_LIGHTS_LIGHT_SAMPLE_H
#include "core/lights/emitter_tree.h"
#include "core/lights/light_layout.h"
#include "core/math/accurate_math.h"
#include "core/math/vector_math.h"
#include "core/rng/sobol_sampler.h"
#include "core/sampling/sampling.h"
#include "core/sampling/spherical_triangle.h"
#include "core/shading/surface_eval.h"

#if !defined(LIGHT_CTX_PARAM) || !defined(LIGHT_CTX) || !defined(LIGHT_HEADER) || !defined(LIGHT_PUNCTUAL) || \
    !defined(LIGHT_CDF) || !defined(LIGHT_EMISSIVE) || !defined(LIGHT_OF_TRIANGLE) || !defined(LIGHT_TREE)
#error "define the LIGHT_* hooks before including core/lights/light_sample.h"
#endif

SST_BEGIN

struct LightSample {
  vec3 wi SST_DEFAULT(vec3(0.0f));  // unit, from the shading point toward the light
  float distance SST_DEFAULT(0.0f);  // to the light point; kInf for directional lights
  vec3 li SST_DEFAULT(vec3(0.0f));  // radiance (area) / intensity / d^2 (point, spot) / irradiance (directional)
  float pdf SST_DEFAULT(0.0f);  // solid-angle pdf incl. the light's pick probability; for delta lights the pick probability
  bool delta SST_DEFAULT(false);  // point, spot, directional: cannot be hit by BSDF sampling
  vec3 point SST_DEFAULT(vec3(0.0f));  // the sampled point (point/spot position; unused for directional)
  vec3 normal SST_DEFAULT(vec3(0.0f));  // geometric normal at the point (0 for punctual lights)
  float offset SST_DEFAULT(0.0f);       // how far a shadow ray's end is lifted along normal (ray_offset.h)
};

// The start of a light path: where it leaves a light, which way, and the flux it carries.
// `weight` is Le cos / (pdf_pick * pdf_position * pdf_direction) (Le cos -> intensity for point
// and spot lights, irradiance for directional ones), so its mean over samples is the total
// power of all lights, in W per RGB channel: N paths each carrying weight / N deliver every
// light's flux in expectation.
struct EmissionSample {
  vec3 position SST_DEFAULT(vec3(0.0f));  // on the light (for a directional light: on a disc outside the scene)
  vec3 normal SST_DEFAULT(vec3(0.0f));  // unit normal of the emitting side of a triangle; 0 for punctual lights
  vec3 direction SST_DEFAULT(vec3(0.0f));  // unit, the direction the light travels
  vec3 weight SST_DEFAULT(vec3(0.0f));  // flux carried, W per RGB channel (see above)
  uint light SST_DEFAULT(0u);  // index in the light distribution (punctual lights first, then triangles)
};

// Where a directional light aims the paths it emits: discs around the point the light's rays
// through `center` start from, of radius `radius`, 4 x radius, 16 x radius, ... up to the scene's
// disc. The first takes half of the paths, the others and the scene's disc share the rest. The
// density of start points then falls off about as 1/distance^2 from the view, as the solid angle
// the view sees a patch under does, so a room lit through its windows in a landscape kilometres
// wide gets its share of the paths and a patch of ground far away stands for its larger area with
// a larger weight (docs/design/lengths.md). radius 0: the scene's disc only.
struct EmissionFocus {
  vec3 center;
  float radius;
};

// How much each focus disc grows over the last, and the most discs before the scene's.
SST_CONSTANT float kFocusGrowth = 4.0f;
SST_CONSTANT int kMaxFocusDiscs = 16;

SST_FUNC EmissionFocus emission_focus_none() {
  EmissionFocus f;
  f.center = vec3(0.0f);
  f.radius = 0.0f;
  return f;
}

// Estimated solid angle (sr) above which a triangle is sampled by solid angle. Measured on the
// Cornell box and the staircase: the RMSE of area sampling matches below it, and the extra
// trigonometry of every solid-angle sample is paid only where it helps.
SST_CONSTANT float kSolidAngleSamplingThreshold = 0.05f;

// ---- the light pick ----------------------------------------------------------------------------

SST_FUNC vec2 light_cdf(LIGHT_CTX_PARAM uint i) {
  LightCdfEntry e = LIGHT_CDF(i);
  return vec2(e.cdf_hi, e.cdf_lo);
}

// cdf[i] > u, exactly as comparing the double cdf with double(u).
SST_FUNC bool light_cdf_greater(LIGHT_CTX_PARAM uint i, float u) {
  LightCdfEntry e = LIGHT_CDF(i);
  return e.cdf_hi > u || (e.cdf_hi == u && e.cdf_lo > 0.0f);
}

// The light for u in [0, 1) (distribution_size > 0): the first entry whose cdf exceeds u, which
// skips zero-weight entries (their cdf equals their predecessor's).
SST_FUNC uint light_pick_index(LIGHT_CTX_PARAM float u) {
  uint n = LIGHT_HEADER.distribution_size;
  uint lo = 0u;
  uint hi = n;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (light_cdf_greater(LIGHT_CTX mid, u)) hi = mid;
    else lo = mid + 1u;
  }
  uint i = min(lo, n - 1u);
  while (i > 0u && LIGHT_CDF(i).pmf == 0.0f) --i;  // u rounding onto a trailing zero-weight entry
  return i;
}

// light_pick_index, and u's position within the entry's share of [0, 1) in u_remapped: itself
// uniform, so a stratified u keeps stratifying what is sampled next (distribution_size > 0).
SST_FUNC uint light_pick(LIGHT_CTX_PARAM float u, SST_OUT(float) u_remapped) {
  uint i = light_pick_index(LIGHT_CTX u);
  vec2 lo = i > 0u ? light_cdf(LIGHT_CTX i - 1u) : vec2(0.0f);
  vec2 width = ff_sub(light_cdf(LIGHT_CTX i), lo);
  u_remapped = 0.0f;
  if (width.x > 0.0f || (width.x == 0.0f && width.y > 0.0f)) {
    float q = ff_div_to_float(ff_sub(vec2(u, 0.0f), lo), width);
    u_remapped = clamp(q, 0.0f, kOneMinusEpsilon);
  }
  return i;
}

// The probability that entry i is picked by power (0 beyond the distribution).
SST_FUNC float light_pmf(LIGHT_CTX_PARAM uint i) { return i < LIGHT_HEADER.distribution_size ? LIGHT_CDF(i).pmf : 0.0f; }

// The header's sampler's pick for shading point p with shading normal n and u in [0, 1): the
// distribution entry, or LIGHT_NONE when no light can contribute; `pmf` its probability and
// `u_remapped` u's position within its share of [0, 1).
SST_FUNC uint light_pick_for(LIGHT_CTX_PARAM vec3 p, vec3 n, float u, SST_OUT(float) pmf, SST_OUT(float) u_remapped) {
  pmf = 0.0f;
  u_remapped = 0.0f;
  uint count = LIGHT_HEADER.distribution_size;
  if (count == 0u) return LIGHT_NONE;
  uint kind = LIGHT_SAMPLER_KIND;
  if (kind == LIGHT_SAMPLER_TREE || kind == LIGHT_SAMPLER_SLC)
    return emitter_tree_pick(LIGHT_CTX p, n, u, pmf, u_remapped);
  if (kind == LIGHT_SAMPLER_UNIFORM) {
    float x = u * float(count);
    uint i = min(uint(x), count - 1u);
    u_remapped = clamp(x - float(i), 0.0f, kOneMinusEpsilon);
    pmf = 1.0f / float(count);
    return i;
  }
  uint i = light_pick(LIGHT_CTX u, u_remapped);
  pmf = light_pmf(LIGHT_CTX i);
  return i;
}

// The probability that light_pick_for(p, n, u) returns entry i for a uniform u.
SST_FUNC float light_pick_pmf(LIGHT_CTX_PARAM vec3 p, vec3 n, uint i) {
  uint count = LIGHT_HEADER.distribution_size;
  if (i >= count) return 0.0f;
  uint kind = LIGHT_SAMPLER_KIND;
  float pmf = 0.0f;
  if (kind == LIGHT_SAMPLER_TREE || kind == LIGHT_SAMPLER_SLC) emitter_tree_pmf(LIGHT_CTX p, n, i, pmf);
  else pmf = kind == LIGHT_SAMPLER_UNIFORM ? 1.0f / float(count) : light_pmf(LIGHT_CTX i);
  return pmf;
}

// ---- geometry ----------------------------------------------------------------------------------

SST_FUNC void light_triangle_vertices(SCENE_CTX_PARAM uint tri, SST_OUT(vec3) v0, SST_OUT(vec3) v1, SST_OUT(vec3) v2) {
  SceneTriangle t = SCENE_TRIANGLE(tri);
  v0 = SCENE_POSITION(t.v0);
  v1 = SCENE_POSITION(t.v1);
  v2 = SCENE_POSITION(t.v2);
}

// Whether an emissive triangle is sampled by solid angle (rather than by area) from p: a pure
// function of the geometry, so sampling and the MIS pdf of a BSDF hit always agree. A cheap
// estimate decides (area x cosine / d^2 from the centroid): solid-angle sampling costs
// trigonometry on every light sample and pays off only where area sampling's 1/d^2 spike is
// large. Exact solid angles are computed only for triangles that qualify.
SST_FUNC bool uses_solid_angle_sampling(vec3 p, vec3 v0, vec3 v1, vec3 v2) {
  float one_third = uintBitsToFloat(0x3EAAAAABu);  // 1.0f / 3.0f
  SST_PRECISE vec3 c = (v0 + v1 + v2) * one_third - p;
  SST_PRECISE vec3 e1 = v1 - v0;
  SST_PRECISE vec3 e2 = v2 - v0;
  vec3 n = cross3(e1, e2);  // twice the area times the unit normal
  float d2 = dot3(c, c);
  SST_PRECISE float estimate = 0.5f * abs(dot3(n, c)) / (d2 * sqrt(d2));
  if (!(estimate >= kSolidAngleSamplingThreshold)) return false;
  float omega = triangle_solid_angle(p, v0, v1, v2);
  return omega >= kMinSphericalSolidAngle && omega <= kMaxSphericalSolidAngle;
}

// glTF spot attenuation: smooth step between the outer and inner cone cosines, squared.
SST_FUNC float spot_attenuation(SST_IN(LightPunctual) light, vec3 light_to_point_unit) {
  float cd = dot3(light.direction, light_to_point_unit);
  SST_PRECISE float cone = light.cos_inner - light.cos_outer;
  float scale = 1.0f / max(0.001f, cone);
  SST_PRECISE float a = (cd - light.cos_outer) * scale;
  a = clamp(a, 0.0f, 1.0f);
  SST_PRECISE float a2 = a * a;
  return a2;
}

// ---- sampling a light from a shading point -----------------------------------------------------

SST_FUNC bool light_sample_punctual(vec3 p, SST_IN(LightPunctual) light, float pick, SST_INOUT(LightSample) s) {
  s.delta = true;
  s.pdf = pick;
  s.offset = 0.0f;  // a point light has no surface to leave; a directional one no end
  if (light.type == LIGHT_DIRECTIONAL) {
    s.wi = -light.direction;
    s.distance = kInf;
    s.li = light.intensity;
    return true;
  }
  s.point = light.position;
  s.normal = vec3(0.0f);
  SST_PRECISE vec3 d = light.position - p;
  float d2 = dot3(d, d);
  if (!(d2 > 0.0f)) return false;
  s.distance = sqrt(d2);
  SST_PRECISE vec3 wi = d / s.distance;
  s.wi = wi;
  SST_PRECISE vec3 li = light.intensity / d2;
  if (light.type == LIGHT_SPOT) li *= spot_attenuation(light, -s.wi);
  s.li = li;
  return true;
}

// The point at barycentrics b of emissive triangle `tri` (vertices v0 v1 v2) seen from p: s gets
// the direction to it, its distance, the radiance it sends toward p, the point, the triangle's
// normal and the point's ray offset (the pdf is the caller's, from `d2` and `cos_light`, the
// normal's cosine with the way to p). False where the point is p or is seen edge-on.
SST_FUNC bool light_triangle_point(SCENE_CTX_PARAM vec3 p, uint tri, vec3 v0, vec3 v1, vec3 v2, vec2 b,
                                   SST_INOUT(LightSample) s, SST_OUT(float) d2, SST_OUT(float) cos_light) {
  cos_light = 0.0f;
  vec3 y = barycentric_mix3(v0, v1, v2, b);
  SST_PRECISE vec3 d = y - p;
  d2 = dot3(d, d);
  if (!(d2 > 0.0f)) return false;
  s.distance = sqrt(d2);
  SST_PRECISE vec3 wi = d / s.distance;
  s.wi = wi;
  vec3 ng = triangle_geometric_normal(SCENE_CTX tri);
  cos_light = dot3(ng, -s.wi);
  if (cos_light == 0.0f) return false;
  s.li = triangle_emission(SCENE_CTX tri, b, cos_light > 0.0f);
  s.point = y;
  s.normal = ng;
  s.offset = triangle_point_offset(v0, v1, v2, y, ng);
  return true;
}

// `b` receives the point's barycentrics on the triangle (the point is barycentric_mix3 of them).
SST_FUNC bool light_sample_triangle(SCENE_CTX_PARAM LIGHT_CTX_PARAM vec3 p, uint k, float pick, vec2 u,
                                    SST_INOUT(LightSample) s, SST_OUT(vec2) b) {
  LightEmissive e = LIGHT_EMISSIVE(k);
  uint tri = e.triangle;
  vec3 v0;
  vec3 v1;
  vec3 v2;
  light_triangle_vertices(SCENE_CTX tri, v0, v1, v2);
  float solid_angle_pdf = 0.0f;
  bool spherical = uses_solid_angle_sampling(p, v0, v1, v2) &&
                   sample_spherical_triangle(p, v0, v1, v2, u, b, solid_angle_pdf);
  if (!spherical) b = sample_uniform_triangle(u.x, u.y);
  float d2;
  float cos_light;
  if (!light_triangle_point(SCENE_CTX p, tri, v0, v1, v2, b, s, d2, cos_light)) return false;
  SST_PRECISE float area_pdf = pick / e.area * d2 / abs(cos_light);
  SST_PRECISE float sphere_pdf = pick * solid_angle_pdf;
  s.pdf = spherical ? sphere_pdf : area_pdf;
  s.delta = false;
  return is_finite(s.pdf) && s.pdf > 0.0f;
}

// What a sample that found no light holds.
SST_FUNC LightSample light_sample_none() {
  LightSample s;
  s.wi = vec3(0.0f);
  s.distance = 0.0f;
  s.li = vec3(0.0f);
  s.pdf = 0.0f;
  s.delta = false;
  s.point = vec3(0.0f);
  s.normal = vec3(0.0f);
  s.offset = 0.0f;
  return s;
}

// A point on light `index` (a distribution entry) for shading point p, the light chosen with
// probability `pick` (folded into LightSample::pdf) and u the 2D sample for the point (u.x is
// free for the triangle's position only when the pick did not use it, or remapped it).
// Returns false when the light sends nothing to p. `b`: the barycentrics of a triangle's point.
SST_FUNC bool light_sample_entry(SCENE_CTX_PARAM LIGHT_CTX_PARAM vec3 p, uint index, float pick, vec2 u,
                                 SST_OUT(LightSample) s, SST_OUT(vec2) b) {
  s = light_sample_none();
  b = vec2(0.0f);
  uint punctual_count = LIGHT_HEADER.punctual_count;
  if (index < punctual_count) return light_sample_punctual(p, LIGHT_PUNCTUAL(index), pick, s);
  return light_sample_triangle(SCENE_CTX LIGHT_CTX p, index - punctual_count, pick, u, s, b);
}

// A light for shading point p with shading normal n (0: none; the tree samplers' receiver
// cosine) with one 2D sample (u.x picks the light and is reused, remapped, for the point on it).
// Returns false when no light can contribute.
// `light` receives the distribution entry and `b` the barycentrics of a triangle's point: what
// names the sample apart from p (ReSTIR's reservoirs keep it, core/restir/restir_di_stages.h).
SST_FUNC bool light_sample_at(SCENE_CTX_PARAM LIGHT_CTX_PARAM vec3 p, vec3 n, vec2 u, SST_OUT(LightSample) s,
                              SST_OUT(uint) light, SST_OUT(vec2) b) {
  float u1;
  float pick;
  light = light_pick_for(LIGHT_CTX p, n, u.x, pick, u1);
  b = vec2(0.0f);
  if (light == LIGHT_NONE) {
    s = light_sample_none();
    return false;
  }
  return light_sample_entry(SCENE_CTX LIGHT_CTX p, light, pick, vec2(u1, u.y), s, b);
}

// light_sample_at without naming the sample.
SST_FUNC bool light_sample(SCENE_CTX_PARAM LIGHT_CTX_PARAM vec3 p, vec3 n, vec2 u, SST_OUT(LightSample) s) {
  uint light;
  vec2 b;
  return light_sample_at(SCENE_CTX LIGHT_CTX p, n, u, s, light, b);
}

// The solid-angle pdf with which light_sample(p, n, ...) picks the point y (geometric normal
// ng_light) on triangle `tri`; 0 for a triangle that is not a light.
SST_FUNC float light_pdf_emissive_hit(SCENE_CTX_PARAM LIGHT_CTX_PARAM vec3 p, vec3 n, uint tri, vec3 y, vec3 ng_light) {
  if (tri >= LIGHT_HEADER.triangle_count) return 0.0f;
  uint index = LIGHT_OF_TRIANGLE(tri);
  if (index == LIGHT_NONE) return 0.0f;
  LightEmissive e = LIGHT_EMISSIVE(index - LIGHT_HEADER.punctual_count);
  float pick = light_pick_pmf(LIGHT_CTX p, n, index);
  if (!(pick > 0.0f)) return 0.0f;
  vec3 v0;
  vec3 v1;
  vec3 v2;
  light_triangle_vertices(SCENE_CTX tri, v0, v1, v2);
  if (uses_solid_angle_sampling(p, v0, v1, v2)) {
    float omega = triangle_solid_angle(p, v0, v1, v2);
    SST_PRECISE float r = pick / omega;
    return omega > 0.0f ? r : 0.0f;
  }
  SST_PRECISE vec3 d = y - p;
  float d2 = dot3(d, d);
  SST_PRECISE float cos_light = abs(dot3(ng_light, d)) / sqrt(d2);
  if (!(cos_light > 0.0f)) return 0.0f;
  SST_PRECISE float r = pick / e.area * d2 / cos_light;
  return r;
}

// ---- sampling the start of a light path --------------------------------------------------------

// A point or spot light emits from its position: uniform sphere, or uniform in the spot's outer
// cone (outside it the glTF attenuation is zero, so no path is wasted on a direction that carries
// nothing).
SST_FUNC bool light_emit_point_or_spot(SST_IN(LightPunctual) light, vec2 u_dir, SST_INOUT(EmissionSample) e) {
  e.position = light.position;
  if (light.type == LIGHT_POINT) {
    e.direction = sample_uniform_sphere(u_dir.x, u_dir.y);
    SST_PRECISE vec3 w = light.intensity * (4.0f * kPi);  // I / pdf, pdf = 1/(4 pi)
    e.weight = w;
    return true;
  }
  SST_PRECISE float one_minus_cos = 1.0f - clamp(light.cos_outer, -1.0f, 1.0f);
  if (!(one_minus_cos > 0.0f)) return false;  // a cone of zero angle emits nothing
  SST_PRECISE float cos_t = 1.0f - u_dir.x * one_minus_cos;
  SST_PRECISE float sin_t2 = 1.0f - cos_t * cos_t;
  float sin_t = sqrt(max(0.0f, sin_t2));
  SST_PRECISE float phi = 2.0f * kPi * u_dir.y;
  SST_PRECISE vec3 local = vec3(sin_t * accurate_cos(phi), sin_t * accurate_sin(phi), cos_t);
  e.direction = normalize3(to_world(basis_from_normal(light.direction), local));
  // I att(w) / pdf, pdf = 1 / (2 pi (1 - cos_outer)): uniform over the cone's solid angle.
  SST_PRECISE float scale = spot_attenuation(light, e.direction) * 2.0f * kPi * one_minus_cos;
  SST_PRECISE vec3 w = light.intensity * scale;
  e.weight = w;
  return true;
}

// The probability of disc k of `discs` focus discs (k = discs: the scene's disc).
SST_FUNC float focus_disc_share(int k, int discs) {
  if (discs == 0) return 1.0f;
  return k == 0 ? 0.5f : 0.5f / float(discs);
}

// The number of focus discs (EmissionFocus) inside a scene disc of radius r.
SST_FUNC int focus_disc_count(float focus_radius, float r) {
  int k = 0;
  float d = focus_radius;
  while (k < kMaxFocusDiscs && d > 0.0f && d < r) {
    ++k;
    d *= kFocusGrowth;
  }
  return k;
}

// A directional light's parallel rays cross the disc of the scene's bounding sphere (centre c,
// radius r) perpendicular to their direction; a uniform point on it, pdf 1/(pi r^2), carries
// E pi r^2. The disc is placed a little more than r upstream of c, so every ray starts outside
// the scene. With a focus (EmissionFocus) the point is drawn on one of its discs (in the same
// plane) or the scene's, with probability focus_disc_share, and carries E / its mixture pdf; a
// point off the scene's disc misses every triangle but still counts.
SST_FUNC bool light_emit_directional(LIGHT_CTX_PARAM SST_IN(LightPunctual) light, vec2 u_pos,
                                     SST_IN(EmissionFocus) focus, SST_INOUT(EmissionSample) e) {
  float r = LIGHT_HEADER.bounds_radius;
  if (!(r > 0.0f) || !is_finite(r)) return false;
  Basis basis = basis_from_normal(light.direction);
  SST_PRECISE vec3 plane_centre = LIGHT_HEADER.bounds_center - light.direction * (1.01f * r);
  SST_PRECISE vec3 focus_centre = focus.center - light.direction * dot3(focus.center - plane_centre, light.direction);
  int discs = focus_disc_count(focus.radius, r);
  // Disc `pick` (discs: the scene's) and u_pos.x's place within its share.
  int pick = 0;
  float below = 0.0f;
  while (pick < discs && u_pos.x >= below + focus_disc_share(pick, discs)) {
    below += focus_disc_share(pick, discs);
    ++pick;
  }
  SST_PRECISE float u = (u_pos.x - below) / focus_disc_share(pick, discs);
  u = clamp(u, 0.0f, kOneMinusEpsilon);
  float disc_r = r;
  if (pick < discs) {
    disc_r = focus.radius;
    for (int k = 0; k < pick; ++k) disc_r *= kFocusGrowth;
  }
  SST_PRECISE float rho = disc_r * sqrt(u);
  SST_PRECISE float phi = 2.0f * kPi * u_pos.y;
  SST_PRECISE vec3 pos = (pick < discs ? focus_centre : plane_centre) + basis.t * (rho * accurate_cos(phi)) +
                         basis.b * (rho * accurate_sin(phi));
  e.position = pos;
  e.direction = light.direction;
  if (discs == 0) {
    SST_PRECISE vec3 w = light.intensity * (kPi * r * r);
    e.weight = w;
    return true;
  }
  // The mixture's pdf at pos, per unit area of the plane.
  SST_PRECISE vec3 from_focus = pos - focus_centre;
  SST_PRECISE vec3 from_centre = pos - plane_centre;
  float f2 = dot3(from_focus, from_focus);
  SST_PRECISE float pdf =
      dot3(from_centre, from_centre) < r * r ? focus_disc_share(discs, discs) / (kPi * r * r) : 0.0f;
  float dk = focus.radius;
  for (int k = 0; k < discs; ++k) {
    SST_PRECISE float term = focus_disc_share(k, discs) / (kPi * dk * dk);
    if (f2 < dk * dk) pdf += term;
    dk *= kFocusGrowth;
  }
  if (!(pdf > 0.0f)) return false;
  SST_PRECISE vec3 w = light.intensity / pdf;
  e.weight = w;
  return true;
}

// Uniform position on emissive triangle k (pdf 1/A) and cosine-weighted direction about the
// emitting side (pdf cos/pi, times 1/2 for the side choice of a double-sided emitter):
// Le cos / (pdf_pos pdf_dir) = Le pi A (x2), the flux one side emits divided by the probability
// of that side.
SST_FUNC bool light_emit_triangle(SCENE_CTX_PARAM LIGHT_CTX_PARAM uint k, vec2 u_pos, vec2 u_dir,
                                  SST_INOUT(EmissionSample) e) {
  LightEmissive em = LIGHT_EMISSIVE(k);
  uint tri = em.triangle;
  vec3 v0;
  vec3 v1;
  vec3 v2;
  light_triangle_vertices(SCENE_CTX tri, v0, v1, v2);
  vec2 b = sample_uniform_triangle(u_pos.x, u_pos.y);
  e.position = barycentric_mix3(v0, v1, v2, b);
  bool double_sided = SCENE_MATERIAL(SCENE_TRIANGLE(tri).material).double_sided != 0u;
  bool front = true;
  float u_side = u_dir.x;
  if (double_sided) {
    front = u_side < 0.5f;
    u_side = front ? remap_below(u_side, 0.5f) : remap_above(u_side, 0.5f);
  }
  vec3 ng = triangle_geometric_normal(SCENE_CTX tri);
  e.normal = front ? ng : -ng;
  vec3 local = sample_cosine_hemisphere(u_side, u_dir.y);
  if (!(local.z > 0.0f)) return false;  // grazing: zero pdf and zero cosine
  e.direction = normalize3(to_world(basis_from_normal(e.normal), local));
  float sides = double_sided ? 2.0f : 1.0f;
  SST_PRECISE float scale = kPi * em.area * sides;
  SST_PRECISE vec3 w = triangle_emission(SCENE_CTX tri, b, front) * scale;
  e.weight = w;
  return true;
}

// Where light leaves distribution entry `index`: a position on it (u_pos) and a direction
// (u_dir), e.weight the emitted flux over the pdf of both (LightSampler::sample_emission without
// the pick). Directional lights read only u_pos, punctual ones only u_dir.
SST_FUNC bool light_emit(SCENE_CTX_PARAM LIGHT_CTX_PARAM uint index, vec2 u_pos, vec2 u_dir,
                         SST_IN(EmissionFocus) focus, SST_INOUT(EmissionSample) e) {
  e.light = index;
  uint punctual_count = LIGHT_HEADER.punctual_count;
  if (index < punctual_count) {
    LightPunctual light = LIGHT_PUNCTUAL(index);
    return light.type == LIGHT_DIRECTIONAL ? light_emit_directional(LIGHT_CTX light, u_pos, focus, e)
                                           : light_emit_point_or_spot(light, u_dir, e);
  }
  return light_emit_triangle(SCENE_CTX LIGHT_CTX index - punctual_count, u_pos, u_dir, e);
}

// A light picked with u_pick in proportion to its power (the distribution light_sample uses), a
// position on it (u_pos) and a direction (u_dir). The pick has its own number (unlike
// light_sample, which remaps one): with a million emissive triangles a remapped 24-bit number
// would leave a few bits for the position on each. Returns false when the path would carry
// nothing (a zero or non-finite weight).
SST_FUNC bool light_sample_emission(SCENE_CTX_PARAM LIGHT_CTX_PARAM float u_pick, vec2 u_pos, vec2 u_dir,
                                    SST_IN(EmissionFocus) focus, SST_OUT(EmissionSample) e) {
  e.position = vec3(0.0f);
  e.normal = vec3(0.0f);
  e.direction = vec3(0.0f);
  e.weight = vec3(0.0f);
  e.light = 0u;
  if (LIGHT_HEADER.distribution_size == 0u) return false;
  uint index = light_pick_index(LIGHT_CTX u_pick);
  float pick = light_pmf(LIGHT_CTX index);
  if (!(pick > 0.0f)) return false;
  if (!light_emit(SCENE_CTX LIGHT_CTX index, u_pos, u_dir, focus, e)) return false;
  SST_PRECISE vec3 w = e.weight / pick;
  e.weight = w;
  return is_finite3(e.weight) && max_component(e.weight) > 0.0f;
}

SST_END

#endif  // SST_CORE_LIGHTS_LIGHT_SAMPLE_H
