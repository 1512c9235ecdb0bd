// The glTF metallic-roughness BRDF every method shades with (docs/design/methods.md), in a local
// shading basis (z = normal), shared C++/GLSL source:
//   f = (1 - metallic) * baseColor / pi  +  D * G * F / (4 |n.wo| |n.wi|)
// D: GGX with alpha = roughness^2; G: Smith height-correlated masking-shadowing; F: Schlick with
// F0 = mix(0.04, baseColor, metallic). Diffuse-only mode keeps just Lambert baseColor / pi.
// The two lobes are added (not energy-mixed), the same for every method.
// ggx_d, smith_g2_height_correlated and schlick_fresnel also serve the many-light samplers' bounds.
#ifndef SST_CORE_MATERIAL_BRDF_H
#define SST_CORE_MATERIAL_BRDF_H
#include "core/math/accurate_math.h"
#include "core/math/vector_math.h"
#include "core/rng/sobol_sampler.h"
#include "core/sampling/sampling.h"

SST_BEGIN

struct Brdf {
  vec3 diffuse SST_DEFAULT(vec3(0.0f));  // (1 - metallic) * baseColor
  vec3 f0 SST_DEFAULT(vec3(0.0f));
  // GGX alpha = roughness^2, at least kMinAlpha: a perfect mirror is a delta the samplers don't model.
  float alpha SST_DEFAULT(1.0f);
  bool specular SST_DEFAULT(false);
};

struct BrdfSample {
  vec3 wi SST_DEFAULT(vec3(0.0f));      // in the shading basis
  vec3 weight SST_DEFAULT(vec3(0.0f));  // f * cos / pdf
  float pdf SST_DEFAULT(0.0f);          // solid angle
};

// alpha below this makes D a spike that float precision cannot integrate; 1e-3 is visually a
// mirror and keeps pdfs finite.
SST_CONSTANT float kMinAlpha = 1e-3f;

SST_FUNC float ggx_d(float n_dot_h, float alpha) {
  if (n_dot_h <= 0.0f) return 0.0f;
  SST_PRECISE float a2 = alpha * alpha;
  SST_PRECISE float d = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  SST_PRECISE float r = a2 / (kPi * d * d);
  return r;
}

SST_FUNC float smith_g1(float n_dot_v, float alpha) {
  SST_PRECISE float a2 = alpha * alpha;
  SST_PRECISE float s = a2 + (1.0f - a2) * n_dot_v * n_dot_v;
  SST_PRECISE float r = 2.0f * n_dot_v / (n_dot_v + sqrt(s));
  return r;
}

SST_FUNC float smith_g2_height_correlated(float n_dot_wo, float n_dot_wi, float alpha) {
  SST_PRECISE float a2 = alpha * alpha;
  SST_PRECISE float so = n_dot_wo * n_dot_wo * (1.0f - a2) + a2;
  SST_PRECISE float si = n_dot_wi * n_dot_wi * (1.0f - a2) + a2;
  SST_PRECISE float lo = n_dot_wi * sqrt(so);
  SST_PRECISE float li = n_dot_wo * sqrt(si);
  SST_PRECISE float r = 2.0f * n_dot_wo * n_dot_wi / (lo + li);
  return lo + li > 0.0f ? r : 0.0f;
}

SST_FUNC vec3 schlick_fresnel(vec3 f0, float cos_theta) {
  float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
  SST_PRECISE float m5 = (m * m) * (m * m) * m;
  SST_PRECISE vec3 r = f0 + (vec3(1.0f) - f0) * m5;
  return r;
}

SST_FUNC Brdf brdf_from_material(vec3 base_color, float metallic, float roughness, bool diffuse_only) {
  Brdf b;
  b.diffuse = vec3(0.0f);
  b.f0 = vec3(0.0f);
  b.alpha = 1.0f;
  b.specular = false;
  if (diffuse_only) {
    b.diffuse = base_color;
    return b;
  }
  metallic = clamp(metallic, 0.0f, 1.0f);
  roughness = clamp(roughness, 0.0f, 1.0f);
  SST_PRECISE vec3 diffuse = (1.0f - metallic) * base_color;
  SST_PRECISE vec3 f0 = vec3(0.04f) * (1.0f - metallic) + base_color * metallic;  // glm::mix
  SST_PRECISE float alpha = roughness * roughness;
  b.diffuse = diffuse;
  b.f0 = f0;
  b.alpha = max(alpha, kMinAlpha);
  b.specular = true;
  return b;
}

// f(wo, wi), without the cosine.
SST_FUNC vec3 brdf_eval(SST_IN(Brdf) b, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  SST_PRECISE vec3 f = b.diffuse * kInvPi;
  if (b.specular) {
    SST_PRECISE vec3 wh = wo + wi;
    vec3 h = normalize3(wh);
    float d = ggx_d(h.z, b.alpha);
    float g = smith_g2_height_correlated(wo.z, wi.z, b.alpha);
    SST_PRECISE float s = d * g / (4.0f * wo.z * wi.z);
    SST_PRECISE vec3 spec = schlick_fresnel(b.f0, dot3(wo, h)) * s;
    f += spec;
  }
  return f;
}

// The probability of choosing the specular lobe when sampling: lobes are picked by their
// approximate albedo so that neither is starved; a pure metal has only the specular lobe.
SST_FUNC float brdf_specular_probability(SST_IN(Brdf) b, vec3 wo) {
  if (!b.specular) return 0.0f;
  float s = luminance(schlick_fresnel(b.f0, max(wo.z, 0.0f)));
  float d = luminance(b.diffuse);
  if (d <= 0.0f) return 1.0f;
  SST_PRECISE float r = s / (s + d);
  return clamp(r, 0.1f, 0.9f);
}

// Solid-angle pdf of brdf_sample, the mixture of both lobes. The VNDF pdf of h is
// G1(wo) D(h) (wo.h) / wo.z; the reflection Jacobian is 1 / (4 wo.h).
SST_FUNC float brdf_pdf(SST_IN(Brdf) b, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  float ps = min(brdf_specular_probability(b, wo), 1.0f);
  SST_PRECISE float pdf = (1.0f - ps) * cosine_hemisphere_pdf(wi.z);
  if (ps > 0.0f) {
    SST_PRECISE vec3 wh = wo + wi;
    vec3 h = normalize3(wh);
    SST_PRECISE float spec = ps * smith_g1(wo.z, b.alpha) * ggx_d(h.z, b.alpha) / (4.0f * wo.z);
    pdf += spec;
  }
  return pdf;
}

// GGX distribution of visible normals (Heitz 2018), wo in the local frame with wo.z > 0.
SST_FUNC vec3 sample_ggx_vndf(vec3 wo, float alpha, float u1, float u2) {
  vec3 vh = normalize3(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  SST_PRECISE float lensq = vh.x * vh.x + vh.y * vh.y;
  SST_PRECISE vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross3(vh, t1);
  float r = sqrt(u1);
  SST_PRECISE float phi = 2.0f * kPi * u2;
  SST_PRECISE float p1 = r * accurate_cos(phi);
  SST_PRECISE float p2 = r * accurate_sin(phi);
  SST_PRECISE float s = 0.5f * (1.0f + vh.z);
  SST_PRECISE float q = 1.0f - p1 * p1;
  p2 = (1.0f - s) * sqrt(max(0.0f, q)) + s * p2;
  SST_PRECISE float q2 = 1.0f - p1 * p1 - p2 * p2;
  SST_PRECISE vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0f, q2)) * vh;
  return normalize3(vec3(alpha * nh.x, alpha * nh.y, max(1e-6f, nh.z)));
}

// Returns false when no direction could be drawn (e.g. wo below the surface). u.x chooses the
// lobe and is reused, remapped, for the direction.
SST_FUNC bool brdf_sample(SST_IN(Brdf) b, vec3 wo, vec2 u, SST_OUT(BrdfSample) s) {
  s.wi = vec3(0.0f);
  s.weight = vec3(0.0f);
  s.pdf = 0.0f;
  if (wo.z <= 0.0f) return false;
  float ps = min(brdf_specular_probability(b, wo), 1.0f);
  vec3 wi;
  if (u.x < ps) {
    vec3 h = sample_ggx_vndf(wo, b.alpha, remap_below(u.x, ps), u.y);
    wi = reflect3(-wo, h);
  } else {
    wi = sample_cosine_hemisphere(ps > 0.0f ? remap_above(u.x, ps) : u.x, u.y);
  }
  if (wi.z <= 0.0f) return false;
  s.wi = wi;
  s.pdf = brdf_pdf(b, wo, wi);
  if (!(s.pdf > 0.0f)) return false;
  SST_PRECISE vec3 w = brdf_eval(b, wo, wi) * (wi.z / s.pdf);
  s.weight = w;
  return true;
}

SST_END

#endif  // SST_CORE_MATERIAL_BRDF_H
