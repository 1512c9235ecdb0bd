#include "core/material/brdf.h"

#include "core/rng/sobol_sampler.h"
#include "core/sampling/sampling.h"

namespace sst {
namespace {
// alpha below this makes D a spike that float precision cannot integrate; 1e-3 is visually a
// mirror and keeps pdfs finite.
constexpr float kMinAlpha = 1e-3f;

// GGX distribution of visible normals (Heitz 2018), wo in the local frame with wo.z > 0.
vec3 sample_ggx_vndf(vec3 wo, float alpha, float u1, float u2) {
  vec3 vh = glm::normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = glm::cross(vh, t1);
  float r = std::sqrt(u1);
  float phi = 2.0f * kPi * u2;
  float p1 = r * std::cos(phi);
  float p2 = r * std::sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

float smith_g1(float n_dot_v, float alpha) {
  float a2 = alpha * alpha;
  return 2.0f * n_dot_v / (n_dot_v + std::sqrt(a2 + (1.0f - a2) * n_dot_v * n_dot_v));
}
}  // namespace

float ggx_d(float n_dot_h, float alpha) {
  if (n_dot_h <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  float d = n_dot_h * n_dot_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

float smith_g2_height_correlated(float n_dot_wo, float n_dot_wi, float alpha) {
  float a2 = alpha * alpha;
  float lo = n_dot_wi * std::sqrt(n_dot_wo * n_dot_wo * (1.0f - a2) + a2);
  float li = n_dot_wo * std::sqrt(n_dot_wi * n_dot_wi * (1.0f - a2) + a2);
  return lo + li > 0.0f ? 2.0f * n_dot_wo * n_dot_wi / (lo + li) : 0.0f;
}

vec3 schlick_fresnel(vec3 f0, float cos_theta) {
  float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  float m5 = (m * m) * (m * m) * m;
  return f0 + (vec3(1.0f) - f0) * m5;
}

Brdf Brdf::from_material(vec3 base_color, float metallic, float roughness, bool diffuse_only) {
  Brdf b;
  if (diffuse_only) {
    b.diffuse = base_color;
    return b;
  }
  metallic = std::clamp(metallic, 0.0f, 1.0f);
  roughness = std::clamp(roughness, 0.0f, 1.0f);
  b.diffuse = (1.0f - metallic) * base_color;
  b.f0 = glm::mix(vec3(0.04f), base_color, metallic);
  b.alpha = std::max(roughness * roughness, kMinAlpha);
  b.specular = true;
  return b;
}

vec3 Brdf::eval(vec3 wo, vec3 wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  vec3 f = diffuse * kInvPi;
  if (specular) {
    vec3 h = glm::normalize(wo + wi);
    float d = ggx_d(h.z, alpha);
    float g = smith_g2_height_correlated(wo.z, wi.z, alpha);
    f += schlick_fresnel(f0, glm::dot(wo, h)) * (d * g / (4.0f * wo.z * wi.z));
  }
  return f;
}

float Brdf::specular_probability(vec3 wo) const {
  if (!specular) return 0.0f;
  // Pick lobes by their approximate albedo so that neither is starved.
  float s = luminance(schlick_fresnel(f0, std::max(wo.z, 0.0f)));
  float d = luminance(diffuse);
  if (d <= 0.0f) return 1.0f;  // a pure metal has only the specular lobe
  return std::clamp(s / (s + d), 0.1f, 0.9f);
}

float Brdf::pdf(vec3 wo, vec3 wi) const {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  float ps = std::min(specular_probability(wo), 1.0f);
  float pdf = (1.0f - ps) * cosine_hemisphere_pdf(wi.z);
  if (ps > 0.0f) {
    vec3 h = glm::normalize(wo + wi);
    // VNDF pdf of h is G1(wo) D(h) (wo.h) / wo.z; the reflection Jacobian is 1 / (4 wo.h).
    pdf += ps * smith_g1(wo.z, alpha) * ggx_d(h.z, alpha) / (4.0f * wo.z);
  }
  return pdf;
}

bool Brdf::sample(vec3 wo, vec2 u, BrdfSample& out) const {
  if (wo.z <= 0.0f) return false;
  float ps = std::min(specular_probability(wo), 1.0f);
  vec3 wi;
  if (u.x < ps) {
    vec3 h = sample_ggx_vndf(wo, alpha, remap_below(u.x, ps), u.y);
    wi = glm::reflect(-wo, h);
  } else {
    wi = sample_cosine_hemisphere(ps > 0.0f ? remap_above(u.x, ps) : u.x, u.y);
  }
  if (wi.z <= 0.0f) return false;
  out.wi = wi;
  out.pdf = pdf(wo, wi);
  if (!(out.pdf > 0.0f)) return false;
  out.weight = eval(wo, wi) * (wi.z / out.pdf);
  return true;
}

}  // namespace sst
