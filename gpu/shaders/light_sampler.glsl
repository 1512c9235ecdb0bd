// The GLSL twin of core/lights/light_sampler.cpp (LightSampler::sample, pdf_emissive_hit,
// sample_emission) and of core/sampling/discrete_distribution.cpp (the light pick), in the C++'s
// operation order and `precise`, over the tables of core/lights/light_layout.h.
//
// The including shader declares, before including this file, the scene buffers
// (SCENE_BUFFERS(first), core/scene/scene_layout.h) and the light buffers
// (LIGHT_BUFFERS(first), core/lights/light_layout.h), e.g.
//   #include "core/scene/scene_layout.h"
//   #include "core/lights/light_layout.h"
//   SCENE_BUFFERS(0)
//   LIGHT_BUFFERS(5)
//   #include "gpu/shaders/light_sampler.glsl"
//
// Same as the CPU: the light picked for a given u (the double CDF is compared exactly through its
// hi/lo float pairs), the remapped u (computed in float-float arithmetic, ~48 bits, then rounded
// as the CPU rounds its double: equal unless the exact value lies within 2^-48 of a rounding
// boundary), the choice between solid-angle and area sampling, and every float of a punctual or
// area-sampled light up to the GPU's sqrt and division (bit for bit on lavapipe). Spherical
// (solid-angle) samples go through asin/atan2/sin/cos (core/math/accurate_math.h, within an
// ulp of glibc's): their pdf within ~1e-5 relative of the CPU's, their point as close as the
// mapping's conditioning allows (core/sampling/spherical_triangle.h).
#ifndef SST_GPU_SHADERS_LIGHT_SAMPLER_GLSL
#define SST_GPU_SHADERS_LIGHT_SAMPLER_GLSL
#include "core/math/accurate_math.h"
#include "core/math/vector_math.h"
#include "core/rng/sobol_sampler.h"
#include "core/sampling/sampling.h"
#include "gpu/shaders/surface.glsl"
#include "core/sampling/spherical_triangle.h"

// sst::LightSample.
struct LightSample {
  vec3 wi;         // unit, from the shading point toward the light
  float distance;  // to the light point; kInf for directional lights
  vec3 li;         // radiance (area) / intensity / d^2 (point, spot) / irradiance (directional)
  float pdf;       // solid-angle pdf incl. the pick probability; for delta lights the pick probability
  bool delta;      // point, spot, directional: cannot be hit by BSDF sampling
  vec3 point;      // the sampled point (point/spot position; unused for directional)
  vec3 normal;     // geometric normal at the point (0 for punctual lights)
};

// sst::EmissionSample: where a light path starts and the flux it carries (see light_sampler.h).
struct EmissionSample {
  vec3 position;
  vec3 normal;     // unit normal of the emitting side of a triangle; 0 for punctual lights
  vec3 direction;  // unit, the direction the light travels
  vec3 weight;     // flux carried, W per RGB channel
  uint light;      // index in the light distribution (punctual lights first, then triangles)
};

// ---- the light pick (DiscreteDistribution::sample) ----------------------------------------------

vec2 light_cdf(uint i) { return vec2(light_distribution[i].cdf_hi, light_distribution[i].cdf_lo); }

// cdf[i] > u, exactly as the CPU compares the double with double(u).
bool light_cdf_greater(uint i, float u) {
  LightCdfEntry e = light_distribution[i];
  return e.cdf_hi > u || (e.cdf_hi == u && e.cdf_lo > 0.0);
}

// The index DiscreteDistribution::sample(u) returns (distribution_size > 0).
uint light_pick_index(float u) {
  uint n = light_header.distribution_size;
  // upper_bound: the first entry whose cdf exceeds u.
  uint lo = 0u, hi = n;
  while (lo < hi) {
    uint mid = lo + (hi - lo) / 2u;
    if (light_cdf_greater(mid, u)) hi = mid;
    else lo = mid + 1u;
  }
  uint i = min(lo, n - 1u);
  while (i > 0u && light_distribution[i].pmf == 0.0) --i;  // u rounding onto a trailing zero-weight entry
  return i;
}

// DiscreteDistribution::sample(u, &u_remapped): also u's position within the entry's share
// (distribution_size > 0).
uint light_pick(float u, out float u_remapped) {
  uint i = light_pick_index(u);
  vec2 lo = i > 0u ? light_cdf(i - 1u) : vec2(0.0);
  vec2 width = ff_sub(light_cdf(i), lo);
  u_remapped = 0.0;
  if (width.x > 0.0 || (width.x == 0.0 && width.y > 0.0)) {
    float q = ff_div_to_float(ff_sub(vec2(u, 0.0), lo), width);
    u_remapped = clamp(q, 0.0, 0.99999994);
  }
  return i;
}

float light_pmf(uint i) { return i < light_header.distribution_size ? light_distribution[i].pmf : 0.0; }

// ---- geometry helpers ---------------------------------------------------------------------------

void light_triangle_vertices(uint tri, out vec3 v0, out vec3 v1, out vec3 v2) {
  SceneTriangle t = scene_triangles[tri];
  v0 = scene_vertices[t.v0].position;
  v1 = scene_vertices[t.v1].position;
  v2 = scene_vertices[t.v2].position;
}

// uses_solid_angle_sampling (core/lights/light_sampler.cpp): a cheap estimate (area x cosine /
// d^2 from the centroid) decides, then the exact solid angle must be in the safe range.
bool uses_solid_angle_sampling(vec3 p, vec3 v0, vec3 v1, vec3 v2) {
  const float one_third = uintBitsToFloat(0x3EAAAAABu);  // 1.0f / 3.0f
  precise vec3 c = (v0 + v1 + v2) * one_third - p;
  precise vec3 e1 = v1 - v0, e2 = v2 - v0;
  vec3 n = cross3(e1, e2);  // twice the area times the unit normal
  float d2 = dot3(c, c);
  precise float estimate = 0.5 * abs(dot3(n, c)) / (d2 * sqrt(d2));
  if (!(estimate >= 0.05)) return false;  // kSolidAngleSamplingThreshold
  float omega = triangle_solid_angle(p, v0, v1, v2);
  return omega >= kMinSphericalSolidAngle && omega <= kMaxSphericalSolidAngle;
}

// glTF spot attenuation: smooth step between the outer and inner cone cosines, squared.
float spot_attenuation(LightPunctual light, vec3 light_to_point_unit) {
  float cd = dot3(light.direction, light_to_point_unit);
  precise float cone = light.cos_inner - light.cos_outer;
  float scale = 1.0 / max(0.001, cone);
  precise float a = (cd - light.cos_outer) * scale;
  a = clamp(a, 0.0, 1.0);
  precise float a2 = a * a;
  return a2;
}

// ---- LightSampler::sample -----------------------------------------------------------------------

bool light_sample_punctual(vec3 p, LightPunctual light, float pick, inout LightSample s) {
  s.delta = true;
  s.pdf = pick;
  if (light.type == LIGHT_DIRECTIONAL) {
    s.wi = -light.direction;
    s.distance = kInf;
    s.li = light.intensity;
    return true;
  }
  s.point = light.position;
  s.normal = vec3(0.0);
  precise vec3 d = light.position - p;
  float d2 = dot3(d, d);
  if (!(d2 > 0.0)) return false;
  s.distance = sqrt(d2);
  precise vec3 wi = d / s.distance;
  s.wi = wi;
  precise vec3 li = light.intensity / d2;
  if (light.type == LIGHT_SPOT) li *= spot_attenuation(light, -s.wi);
  s.li = li;
  return true;
}

bool light_sample_triangle(vec3 p, uint k, float pick, vec2 u, inout LightSample s) {
  LightEmissive e = light_emissive[k];
  uint tri = e.triangle;
  vec3 v0, v1, v2;
  light_triangle_vertices(tri, v0, v1, v2);
  vec2 b;
  float solid_angle_pdf = 0.0;
  bool spherical = uses_solid_angle_sampling(p, v0, v1, v2) &&
                   sample_spherical_triangle(p, v0, v1, v2, u, b, solid_angle_pdf);
  if (!spherical) b = sample_uniform_triangle(u.x, u.y);
  vec3 y = scene_interpolate3(v0, v1, v2, b);
  precise vec3 d = y - p;
  float d2 = dot3(d, d);
  if (!(d2 > 0.0)) return false;
  s.distance = sqrt(d2);
  precise vec3 wi = d / s.distance;
  s.wi = wi;
  vec3 ng = triangle_geometric_normal(tri);
  float cos_light = dot3(ng, -s.wi);
  if (cos_light == 0.0) return false;
  s.li = triangle_emission(tri, b, cos_light > 0.0);
  s.point = y;
  s.normal = ng;
  precise float area_pdf = pick / e.area * d2 / abs(cos_light);
  precise float sphere_pdf = pick * solid_angle_pdf;
  s.pdf = spherical ? sphere_pdf : area_pdf;
  s.delta = false;
  return is_finite(s.pdf) && s.pdf > 0.0;
}

// LightSampler::sample: a light for shading point p with one 2D sample (u.x picks the light and
// is reused, remapped, for the point on it). Returns false when no light can contribute.
bool light_sample(vec3 p, vec2 u, out LightSample s) {
  s.wi = vec3(0.0);
  s.distance = 0.0;
  s.li = vec3(0.0);
  s.pdf = 0.0;
  s.delta = false;
  s.point = vec3(0.0);
  s.normal = vec3(0.0);
  if (light_header.distribution_size == 0u) return false;
  float u1;
  uint index = light_pick(u.x, u1);
  float pick = light_pmf(index);
  if (index < light_header.punctual_count) return light_sample_punctual(p, light_punctual[index], pick, s);
  return light_sample_triangle(p, index - light_header.punctual_count, pick, vec2(u1, u.y), s);
}

// LightSampler::pdf_emissive_hit: the solid-angle pdf with which light_sample picks the point y
// (geometric normal ng_light) on triangle `tri` from p; 0 for a triangle that is not a light.
float light_pdf_emissive_hit(vec3 p, uint tri, vec3 y, vec3 ng_light) {
  if (tri >= light_header.triangle_count) return 0.0;
  uint index = light_of_triangle[tri];
  if (index == LIGHT_NONE) return 0.0;
  LightEmissive e = light_emissive[index - light_header.punctual_count];
  float pick = light_pmf(index);
  vec3 v0, v1, v2;
  light_triangle_vertices(tri, v0, v1, v2);
  if (uses_solid_angle_sampling(p, v0, v1, v2)) {
    float omega = triangle_solid_angle(p, v0, v1, v2);
    precise float r = pick / omega;
    return omega > 0.0 ? r : 0.0;
  }
  precise vec3 d = y - p;
  float d2 = dot3(d, d);
  precise float cos_light = abs(dot3(ng_light, d)) / sqrt(d2);
  if (!(cos_light > 0.0)) return 0.0;
  precise float r = pick / e.area * d2 / cos_light;
  return r;
}

// ---- LightSampler::sample_emission --------------------------------------------------------------

// A point or spot light emits from its position: uniform sphere, or uniform in the spot's outer cone.
bool light_emit_point_or_spot(LightPunctual light, vec2 u_dir, inout EmissionSample e) {
  e.position = light.position;
  if (light.type == LIGHT_POINT) {
    e.direction = sample_uniform_sphere(u_dir.x, u_dir.y);
    precise vec3 w = light.intensity * (4.0 * kPi);  // I / pdf, pdf = 1/(4 pi)
    e.weight = w;
    return true;
  }
  precise float one_minus_cos = 1.0 - clamp(light.cos_outer, -1.0, 1.0);
  if (!(one_minus_cos > 0.0)) return false;  // a cone of zero angle emits nothing
  precise float cos_t = 1.0 - u_dir.x * one_minus_cos;
  precise float sin_t2 = 1.0 - cos_t * cos_t;
  float sin_t = sqrt(max(0.0, sin_t2));
  precise float phi = 2.0 * kPi * u_dir.y;
  precise vec3 local = vec3(sin_t * accurate_cos(phi), sin_t * accurate_sin(phi), cos_t);
  e.direction = normalize3(to_world(basis_from_normal(light.direction), local));
  // I att(w) / pdf, pdf = 1 / (2 pi (1 - cos_outer)): uniform over the cone's solid angle.
  precise float scale = spot_attenuation(light, e.direction) * 2.0 * kPi * one_minus_cos;
  precise vec3 w = light.intensity * scale;
  e.weight = w;
  return true;
}

// A directional light's rays cross the disc of the scene's bounding sphere perpendicular to them,
// placed a little more than its radius upstream of the centre.
bool light_emit_directional(LightPunctual light, vec2 u_pos, inout EmissionSample e) {
  float r = light_header.bounds_radius;
  if (!(r > 0.0) || !is_finite(r)) return false;
  Basis basis = basis_from_normal(light.direction);
  precise float rho = r * sqrt(u_pos.x);
  precise float phi = 2.0 * kPi * u_pos.y;
  precise vec3 pos = light_header.bounds_center - light.direction * (1.01 * r) + basis.t * (rho * accurate_cos(phi)) +
                     basis.b * (rho * accurate_sin(phi));
  e.position = pos;
  e.direction = light.direction;
  precise vec3 w = light.intensity * (kPi * r * r);
  e.weight = w;
  return true;
}

// Uniform position on emissive triangle k, cosine-weighted direction about the emitting side (a
// double-sided emitter first picks its side with probability 1/2).
bool light_emit_triangle(uint k, vec2 u_pos, vec2 u_dir, inout EmissionSample e) {
  LightEmissive em = light_emissive[k];
  uint tri = em.triangle;
  vec3 v0, v1, v2;
  light_triangle_vertices(tri, v0, v1, v2);
  vec2 b = sample_uniform_triangle(u_pos.x, u_pos.y);
  e.position = scene_interpolate3(v0, v1, v2, b);
  bool double_sided = scene_materials[scene_triangles[tri].material].double_sided != 0u;
  bool front = true;
  float u_side = u_dir.x;
  if (double_sided) {
    front = u_side < 0.5;
    u_side = front ? remap_below(u_side, 0.5) : remap_above(u_side, 0.5);
  }
  vec3 ng = triangle_geometric_normal(tri);
  e.normal = front ? ng : -ng;
  vec3 local = sample_cosine_hemisphere(u_side, u_dir.y);
  if (!(local.z > 0.0)) return false;  // grazing: zero pdf and zero cosine
  e.direction = normalize3(to_world(basis_from_normal(e.normal), local));
  float sides = double_sided ? 2.0 : 1.0;
  precise float scale = kPi * em.area * sides;
  precise vec3 w = triangle_emission(tri, b, front) * scale;
  e.weight = w;
  return true;
}

// LightSampler::sample_emission: a light picked with u_pick in proportion to its power, a position
// on it (u_pos) and a direction (u_dir). Returns false when the path would carry nothing.
bool light_sample_emission(float u_pick, vec2 u_pos, vec2 u_dir, out EmissionSample e) {
  e.position = vec3(0.0);
  e.normal = vec3(0.0);
  e.direction = vec3(0.0);
  e.weight = vec3(0.0);
  e.light = 0u;
  if (light_header.distribution_size == 0u) return false;
  uint index = light_pick_index(u_pick);
  float pick = light_pmf(index);
  if (!(pick > 0.0)) return false;
  e.light = index;
  bool ok;
  if (index < light_header.punctual_count) {
    LightPunctual light = light_punctual[index];
    ok = light.type == LIGHT_DIRECTIONAL ? light_emit_directional(light, u_pos, e)
                                         : light_emit_point_or_spot(light, u_dir, e);
  } else {
    ok = light_emit_triangle(index - light_header.punctual_count, u_pos, u_dir, e);
  }
  if (!ok) return false;
  precise vec3 w = e.weight / pick;
  e.weight = w;
  return is_finite3(e.weight) && max_component(e.weight) > 0.0;
}

#endif  // SST_GPU_SHADERS_LIGHT_SAMPLER_GLSL
