// The GLSL twin of core/material/brdf.{h,cpp}: the glTF metallic-roughness BRDF (Lambert + GGX,
// Smith height-correlated, Schlick), its lobe-mixture sampling and pdf, in the C++'s operation order.
#ifndef SST_GPU_SHADERS_BRDF_GLSL
#define SST_GPU_SHADERS_BRDF_GLSL
#include "gpu/shaders/math.glsl"
#include "gpu/shaders/sampling.glsl"

struct Brdf {
  vec3 diffuse;  // (1 - metallic) * baseColor
  vec3 f0;
  float alpha;
  bool specular;
};

struct BrdfSample {
  vec3 wi;      // local frame
  vec3 weight;  // f * cos / pdf
  float pdf;
};

const float kMinAlpha = 1e-3;

float ggx_d(float n_dot_h, float alpha) {
  if (n_dot_h <= 0.0) return 0.0;
  precise float a2 = alpha * alpha;
  precise float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  precise float r = a2 / (kPi * d * d);
  return r;
}

float smith_g1(float n_dot_v, float alpha) {
  precise float a2 = alpha * alpha;
  precise float s = a2 + (1.0 - a2) * n_dot_v * n_dot_v;
  precise float r = 2.0 * n_dot_v / (n_dot_v + sqrt(s));
  return r;
}

float smith_g2_height_correlated(float n_dot_wo, float n_dot_wi, float alpha) {
  precise float a2 = alpha * alpha;
  precise float so = n_dot_wo * n_dot_wo * (1.0 - a2) + a2;
  precise float si = n_dot_wi * n_dot_wi * (1.0 - a2) + a2;
  precise float lo = n_dot_wi * sqrt(so);
  precise float li = n_dot_wo * sqrt(si);
  precise float r = 2.0 * n_dot_wo * n_dot_wi / (lo + li);
  return lo + li > 0.0 ? r : 0.0;
}

vec3 schlick_fresnel(vec3 f0, float cos_theta) {
  float m = clamp(1.0 - cos_theta, 0.0, 1.0);
  precise float m5 = (m * m) * (m * m) * m;
  precise vec3 r = f0 + (vec3(1.0) - f0) * m5;
  return r;
}

Brdf brdf_from_material(vec3 base_color, float metallic, float roughness, bool diffuse_only) {
  Brdf b;
  b.diffuse = vec3(0.0);
  b.f0 = vec3(0.0);
  b.alpha = 1.0;
  b.specular = false;
  if (diffuse_only) {
    b.diffuse = base_color;
    return b;
  }
  metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
  precise vec3 diffuse = (1.0 - metallic) * base_color;
  precise vec3 f0 = vec3(0.04) * (1.0 - metallic) + base_color * metallic;  // glm::mix
  precise float alpha = roughness * roughness;
  b.diffuse = diffuse;
  b.f0 = f0;
  b.alpha = max(alpha, kMinAlpha);
  b.specular = true;
  return b;
}

vec3 brdf_eval(Brdf b, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  precise vec3 f = b.diffuse * kInvPi;
  if (b.specular) {
    precise vec3 wh = wo + wi;
    vec3 h = glm_normalize(wh);
    float d = ggx_d(h.z, b.alpha);
    float g = smith_g2_height_correlated(wo.z, wi.z, b.alpha);
    precise float s = d * g / (4.0 * wo.z * wi.z);
    precise vec3 spec = schlick_fresnel(b.f0, glm_dot(wo, h)) * s;
    f += spec;
  }
  return f;
}

float brdf_specular_probability(Brdf b, vec3 wo) {
  if (!b.specular) return 0.0;
  float s = luminance(schlick_fresnel(b.f0, max(wo.z, 0.0)));
  float d = luminance(b.diffuse);
  if (d <= 0.0) return 1.0;
  precise float r = s / (s + d);
  return clamp(r, 0.1, 0.9);
}

float brdf_pdf(Brdf b, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  float ps = min(brdf_specular_probability(b, wo), 1.0);
  precise float pdf = (1.0 - ps) * cosine_hemisphere_pdf(wi.z);
  if (ps > 0.0) {
    precise vec3 wh = wo + wi;
    vec3 h = glm_normalize(wh);
    precise float spec = ps * smith_g1(wo.z, b.alpha) * ggx_d(h.z, b.alpha) / (4.0 * wo.z);
    pdf += spec;
  }
  return pdf;
}

// GGX distribution of visible normals (Heitz 2018), wo in the local frame with wo.z > 0.
vec3 sample_ggx_vndf(vec3 wo, float alpha, float u1, float u2) {
  vec3 vh = glm_normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  precise float lensq = vh.x * vh.x + vh.y * vh.y;
  precise vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) / sqrt(lensq) : vec3(1.0, 0.0, 0.0);
  vec3 t2 = glm_cross(vh, t1);
  float r = sqrt(u1);
  precise float phi = 2.0 * kPi * u2;
  precise float p1 = r * accurate_cos(phi);
  precise float p2 = r * accurate_sin(phi);
  precise float s = 0.5 * (1.0 + vh.z);
  precise float q = 1.0 - p1 * p1;
  p2 = (1.0 - s) * sqrt(max(0.0, q)) + s * p2;
  precise float q2 = 1.0 - p1 * p1 - p2 * p2;
  precise vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, q2)) * vh;
  return glm_normalize(vec3(alpha * nh.x, alpha * nh.y, max(1e-6, nh.z)));
}

// glm::reflect(i, n) = i - n * dot(n, i) * 2.
vec3 glm_reflect(vec3 i, vec3 n) {
  precise vec3 r = i - n * glm_dot(n, i) * 2.0;
  return r;
}

bool brdf_sample(Brdf b, vec3 wo, vec2 u, out BrdfSample s) {
  s.wi = vec3(0.0);
  s.weight = vec3(0.0);
  s.pdf = 0.0;
  if (wo.z <= 0.0) return false;
  float ps = min(brdf_specular_probability(b, wo), 1.0);
  vec3 wi;
  if (u.x < ps) {
    vec3 h = sample_ggx_vndf(wo, b.alpha, remap_below(u.x, ps), u.y);
    wi = glm_reflect(-wo, h);
  } else {
    wi = sample_cosine_hemisphere(ps > 0.0 ? remap_above(u.x, ps) : u.x, u.y);
  }
  if (wi.z <= 0.0) return false;
  s.wi = wi;
  s.pdf = brdf_pdf(b, wo, wi);
  if (!(s.pdf > 0.0)) return false;
  precise vec3 w = brdf_eval(b, wo, wi) * (wi.z / s.pdf);
  s.weight = w;
  return true;
}

#endif
