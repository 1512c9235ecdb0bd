#include "core/lights/light_sampler.h"

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

uint32_t light_type_code(LightType type) {
  switch (type) {
    case LightType::Spot: return LIGHT_SPOT;
    case LightType::Directional: return LIGHT_DIRECTIONAL;
    case LightType::Point:
    default: return LIGHT_POINT;
  }
}

// A double cdf value as hi + lo floats: comparing (hi, lo) with a float u gives the double's answer.
glsl::LightCdfEntry cdf_entry(double cdf, float pmf) {
  glsl::LightCdfEntry e{};
  e.cdf_hi = float(cdf);
  e.cdf_lo = float(cdf - double(e.cdf_hi));
  e.pmf = pmf;
  e.reserved = 0u;
  return e;
}
}  // namespace

size_t PackedLights::bytes() const {
  return sizeof header + punctual.size() * sizeof(glsl::LightPunctual) +
         distribution.size() * sizeof(glsl::LightCdfEntry) + emissive.size() * sizeof(glsl::LightEmissive) +
         light_of_triangle.size() * sizeof(uint32_t);
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
  packed_.light_of_triangle.assign(scene.triangles.size(), LIGHT_NONE);
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    float scale = material_scale[scene.triangle_material[t]];
    if (!(scale > 0.0f)) continue;
    float area = triangle_area(scene, t);
    if (!(area > 0.0f)) continue;
    packed_.light_of_triangle[t] = uint32_t(weights.size());
    weights.push_back(double(area) * scale);
    glsl::LightEmissive e{};
    e.triangle = t;
    e.area = area;
    packed_.emissive.push_back(e);
  }
  distribution_ = DiscreteDistribution(weights);

  glsl::LightHeader& h = packed_.header;
  h.punctual_count = uint32_t(scene.lights.size());
  h.emissive_count = uint32_t(packed_.emissive.size());
  // An empty distribution picks nothing: the sampling tests distribution_size == 0.
  h.distribution_size = distribution_.empty() ? 0u : uint32_t(distribution_.size());
  h.triangle_count = uint32_t(scene.triangles.size());
  h.bounds_center = scene.bounds.center();
  h.bounds_radius = 0.5f * scene.bounds.diagonal();
  packed_.punctual.reserve(scene.lights.size());
  for (const PunctualLight& l : scene.lights) {
    glsl::LightPunctual p{};
    p.position = l.position;
    p.type = light_type_code(l.type);
    p.direction = l.direction;
    p.cos_inner = l.cos_inner;
    p.intensity = l.intensity;
    p.cos_outer = l.cos_outer;
    packed_.punctual.push_back(p);
  }
  if (!distribution_.empty()) {
    packed_.distribution.reserve(distribution_.size());
    for (size_t i = 0; i < distribution_.size(); ++i)
      packed_.distribution.push_back(cdf_entry(distribution_.cdf()[i], distribution_.pmfs()[i]));
  }
}

}  // namespace sst
