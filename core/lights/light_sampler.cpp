#include "core/lights/light_sampler.h"

#include "core/shading/surface.h"
#include "core/rng/sobol_sampler.h"
#include "core/sampling/sampling.h"
#include "core/sampling/spherical_triangle.h"

namespace sst {
namespace {
// Luminance of a texture's mean, so a textured emitter's power estimate reflects its pattern.
float mean_luminance(const Texture& t) {
  if (t.texel_count() == 0) return 1.0f;
  double sum = 0.0;
  for (size_t i = 0; i < t.texel_count(); ++i) sum += luminance(vec3(t.texel(i)));
  return float(sum / double(t.texel_count()));
}

double punctual_power(const PunctualLight& light, const Bounds3& bounds) {
  float i = luminance(light.intensity);
  switch (light.type) {
    case LightType::Point: return 4.0 * kPi * i;
    case LightType::Spot: {
      // Cone of the average of the inner and outer angles: a close, cheap estimate.
      float cos_mid = 0.5f * (light.cos_inner + light.cos_outer);
      return 2.0 * kPi * (1.0 - cos_mid) * i;
    }
    case LightType::Directional: {
      // Irradiance over the disc the scene's bounding sphere casts.
      float r = 0.5f * bounds.diagonal();
      return kPi * r * r * i;
    }
  }
  return 0.0;
}

// Emission from a point or spot light at its position (see sample_emission in the header).
// The spot's directions are drawn inside its outer cone only: outside it the glTF attenuation is
// zero, so nothing is lost and no path is wasted on a direction that carries nothing.
bool emit_point_or_spot(const PunctualLight& light, vec2 u_dir, EmissionSample& out) {
  out.position = light.position;
  if (light.type == LightType::Point) {
    out.direction = sample_uniform_sphere(u_dir.x, u_dir.y);
    out.weight = light.intensity * (4.0f * kPi);  // I / pdf, pdf = 1/(4 pi)
    return true;
  }
  float one_minus_cos = 1.0f - std::clamp(light.cos_outer, -1.0f, 1.0f);
  if (!(one_minus_cos > 0.0f)) return false;  // a cone of zero angle emits nothing
  float cos_t = 1.0f - u_dir.x * one_minus_cos;
  float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  float phi = 2.0f * kPi * u_dir.y;
  vec3 local(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
  out.direction = glm::normalize(to_world(basis_from_normal(light.direction), local));
  // I att(w) / pdf, pdf = 1 / (2 pi (1 - cos_outer)): uniform over the cone's solid angle.
  out.weight = light.intensity * (spot_attenuation(light, out.direction) * 2.0f * kPi * one_minus_cos);
  return true;
}

// A directional light's parallel rays cross the disc of the bounding sphere (centre c, radius r)
// perpendicular to their direction; a uniform point on it, pdf 1/(pi r^2), carries E pi r^2.
// The disc is placed a little more than r upstream of c, so every ray starts outside the scene.
bool emit_directional(const PunctualLight& light, const Bounds3& bounds, vec2 u_pos, EmissionSample& out) {
  float r = 0.5f * bounds.diagonal();
  if (!(r > 0.0f) || !std::isfinite(r)) return false;
  Basis basis = basis_from_normal(light.direction);
  float rho = r * std::sqrt(u_pos.x), phi = 2.0f * kPi * u_pos.y;
  out.position = bounds.center() - light.direction * (1.01f * r) +
                 basis.t * (rho * std::cos(phi)) + basis.b * (rho * std::sin(phi));
  out.direction = light.direction;
  out.weight = light.intensity * (kPi * r * r);
  return true;
}
}  // namespace

bool uses_solid_angle_sampling(vec3 p, vec3 v0, vec3 v1, vec3 v2) {
  // A cheap estimate decides (area x cosine / d^2 from the centroid): solid-angle sampling
  // costs trigonometry on every light sample and pays off only where area sampling's 1/d^2
  // spike is large. Exact solid angles are computed only for triangles that qualify.
  vec3 c = (v0 + v1 + v2) * (1.0f / 3.0f) - p;
  vec3 n = glm::cross(v1 - v0, v2 - v0);  // twice the area times the unit normal
  float d2 = glm::dot(c, c);
  float estimate = 0.5f * std::abs(glm::dot(n, c)) / (d2 * std::sqrt(d2));
  if (!(estimate >= kSolidAngleSamplingThreshold)) return false;
  float omega = triangle_solid_angle(p, v0, v1, v2);
  return omega >= kMinSphericalSolidAngle && omega <= kMaxSphericalSolidAngle;
}

float spot_attenuation(const PunctualLight& light, vec3 light_to_point_unit) {
  float cd = glm::dot(light.direction, light_to_point_unit);
  float scale = 1.0f / std::max(0.001f, light.cos_inner - light.cos_outer);
  float a = std::clamp((cd - light.cos_outer) * scale, 0.0f, 1.0f);
  return a * a;
}

LightSampler::LightSampler(const Scene& scene) : scene_(&scene) {
  std::vector<double> weights;
  for (const PunctualLight& light : scene.lights) weights.push_back(punctual_power(light, scene.bounds));
  std::vector<float> material_scale(scene.materials.size(), 0.0f);
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    float tex = mat.emissive_texture >= 0 && size_t(mat.emissive_texture) < scene.textures.size()
                    ? mean_luminance(scene.textures[mat.emissive_texture])
                    : 1.0f;
    material_scale[m] = luminance(mat.emission) * tex * kPi * (mat.double_sided ? 2.0f : 1.0f);
  }
  light_of_triangle_.assign(scene.triangles.size(), UINT32_MAX);
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    float scale = material_scale[scene.triangle_material[t]];
    if (!(scale > 0.0f)) continue;
    float area = triangle_area(scene, t);
    if (!(area > 0.0f)) continue;
    light_of_triangle_[t] = uint32_t(weights.size());
    weights.push_back(double(area) * scale);
    emissive_triangles_.push_back(t);
    triangle_area_.push_back(area);
  }
  distribution_ = DiscreteDistribution(weights);
}

bool LightSampler::sample(vec3 p, vec2 u, LightSample& out) const {
  if (empty()) return false;
  float u1 = 0.0f, u2 = u.y;
  uint32_t index = distribution_.sample(u.x, &u1);
  float pick = distribution_.pmf(index);
  if (index < scene_->lights.size()) {
    const PunctualLight& light = scene_->lights[index];
    out.delta = true;
    out.pdf = pick;
    if (light.type == LightType::Directional) {
      out.wi = -light.direction;
      out.distance = kInf;
      out.li = light.intensity;
      return true;
    }
    out.point = light.position;
    out.normal = vec3(0.0f);
    vec3 d = light.position - p;
    float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f)) return false;
    out.distance = std::sqrt(d2);
    out.wi = d / out.distance;
    out.li = light.intensity / d2;
    if (light.type == LightType::Spot) out.li *= spot_attenuation(light, -out.wi);
    return true;
  }
  size_t k = index - scene_->lights.size();
  uint32_t tri = emissive_triangles_[k];
  const uvec3& t = scene_->triangles[tri];
  vec3 v0 = scene_->positions[t.x], v1 = scene_->positions[t.y], v2 = scene_->positions[t.z];
  vec2 b;
  float solid_angle_pdf = 0.0f;
  bool spherical = uses_solid_angle_sampling(p, v0, v1, v2) &&
                   sample_spherical_triangle(p, v0, v1, v2, vec2(u1, u2), b, solid_angle_pdf);
  if (!spherical) b = sample_uniform_triangle(u1, u2);
  vec3 y = (1.0f - b.x - b.y) * v0 + b.x * v1 + b.y * v2;
  vec3 d = y - p;
  float d2 = glm::dot(d, d);
  if (!(d2 > 0.0f)) return false;
  out.distance = std::sqrt(d2);
  out.wi = d / out.distance;
  vec3 ng = triangle_geometric_normal(*scene_, tri);
  float cos_light = glm::dot(ng, -out.wi);
  if (cos_light == 0.0f) return false;
  out.li = triangle_emission(*scene_, tri, b, cos_light > 0.0f);
  out.point = y;
  out.normal = ng;
  out.pdf = spherical ? pick * solid_angle_pdf : pick / triangle_area_[k] * d2 / std::abs(cos_light);
  out.delta = false;
  return std::isfinite(out.pdf) && out.pdf > 0.0f;
}

float LightSampler::pdf_emissive_hit(vec3 p, uint32_t tri, vec3 y, vec3 ng_light) const {
  if (tri >= light_of_triangle_.size() || light_of_triangle_[tri] == UINT32_MAX) return 0.0f;
  uint32_t index = light_of_triangle_[tri];
  size_t k = index - scene_->lights.size();
  const uvec3& t = scene_->triangles[tri];
  vec3 v0 = scene_->positions[t.x], v1 = scene_->positions[t.y], v2 = scene_->positions[t.z];
  if (uses_solid_angle_sampling(p, v0, v1, v2)) {
    float omega = triangle_solid_angle(p, v0, v1, v2);
    return omega > 0.0f ? distribution_.pmf(index) / omega : 0.0f;
  }
  vec3 d = y - p;
  float d2 = glm::dot(d, d);
  float cos_light = std::abs(glm::dot(ng_light, d)) / std::sqrt(d2);
  if (!(cos_light > 0.0f)) return 0.0f;
  return distribution_.pmf(index) / triangle_area_[k] * d2 / cos_light;
}

bool LightSampler::sample_emission(float u_pick, vec2 u_pos, vec2 u_dir, EmissionSample& out) const {
  out = EmissionSample{};
  if (empty()) return false;
  uint32_t index = distribution_.sample(u_pick);
  float pick = distribution_.pmf(index);
  if (!(pick > 0.0f)) return false;
  out.light = index;
  bool ok = false;
  if (index < scene_->lights.size()) {
    const PunctualLight& light = scene_->lights[index];
    ok = light.type == LightType::Directional ? emit_directional(light, scene_->bounds, u_pos, out)
                                              : emit_point_or_spot(light, u_dir, out);
  } else {
    ok = emit_triangle(index - scene_->lights.size(), u_pos, u_dir, out);
  }
  if (!ok) return false;
  out.weight /= pick;
  return is_finite(out.weight) && max_component(out.weight) > 0.0f;
}

// Uniform position (pdf 1/A) and cosine-weighted direction about the emitting side (pdf cos/pi,
// times 1/2 for the side choice of a double-sided emitter): Le cos / (pdf_pos pdf_dir) =
// Le pi A (x2), the flux one side emits (Le pi A) divided by the probability of that side.
bool LightSampler::emit_triangle(size_t k, vec2 u_pos, vec2 u_dir, EmissionSample& out) const {
  uint32_t tri = emissive_triangles_[k];
  const uvec3& t = scene_->triangles[tri];
  vec2 b = sample_uniform_triangle(u_pos.x, u_pos.y);
  out.position = (1.0f - b.x - b.y) * scene_->positions[t.x] + b.x * scene_->positions[t.y] +
                 b.y * scene_->positions[t.z];
  bool double_sided = scene_->materials[scene_->triangle_material[tri]].double_sided;
  bool front = true;
  float u_side = u_dir.x;
  if (double_sided) {
    front = u_side < 0.5f;
    u_side = front ? remap_below(u_side, 0.5f) : remap_above(u_side, 0.5f);
  }
  vec3 ng = triangle_geometric_normal(*scene_, tri);
  out.normal = front ? ng : -ng;
  vec3 local = sample_cosine_hemisphere(u_side, u_dir.y);
  if (!(local.z > 0.0f)) return false;  // grazing: zero pdf and zero cosine
  out.direction = glm::normalize(to_world(basis_from_normal(out.normal), local));
  float sides = double_sided ? 2.0f : 1.0f;
  out.weight = triangle_emission(*scene_, tri, b, front) * (kPi * triangle_area_[k] * sides);
  return true;
}

}  // namespace sst
