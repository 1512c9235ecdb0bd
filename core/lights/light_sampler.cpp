#include "core/lights/light_sampler.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/util/error.h"

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
  e.tree_node = LIGHT_NONE;
  return e;
}

// The emitter tree's leaf for a punctual light (EmitterNode, core/lights/light_layout.h): a point
// light emits every way (theta_o = pi, theta_e = pi/2, as pbrt-v4); a spot light at full
// strength within its inner cone and nothing beyond the outer one (theta_o = inner, theta_o +
// theta_e = outer); a directional light is kept beside the tree with its irradiance.
glsl::EmitterNode punctual_leaf(const PunctualLight& light) {
  glsl::EmitterNode n{};
  n.lo = light.position;
  n.hi = light.position;
  n.intensity = luminance(light.intensity);
  n.axis = vec3(0.0f, 0.0f, 1.0f);
  n.cos_o = -1.0f;
  n.cos_e = 0.0f;
  n.entry = LIGHT_NONE;
  if (light.type == LightType::Spot) {
    n.axis = light.direction;
    double inner = std::acos(std::clamp(double(light.cos_inner), -1.0, 1.0));
    double outer = std::acos(std::clamp(double(light.cos_outer), -1.0, 1.0));
    n.cos_o = float(std::cos(std::min(inner, outer)));
    n.cos_e = float(std::cos(std::max(0.0, outer - inner) + kConeSlack));
  } else if (light.type == LightType::Directional) {
    n.lo = n.hi = vec3(0.0f);
    n.axis = light.direction;
    n.flags = EMITTER_DIRECTIONAL;
  }
  return n;
}

// The leaf of an emissive triangle: its box, its normal (the front side's: triangle_emission
// emits from the back only for a double-sided material), Le A for intensity.
glsl::EmitterNode triangle_leaf(const Scene& scene, uint32_t t, float mean_radiance, bool double_sided, float area) {
  glsl::EmitterNode n{};
  vec3 v0, v1, v2;
  light_triangle_vertices(scene, t, v0, v1, v2);
  n.lo = glm::min(v0, glm::min(v1, v2));
  n.hi = glm::max(v0, glm::max(v1, v2));
  n.intensity = mean_radiance * area;
  n.axis = triangle_geometric_normal(scene, t);
  n.cos_o = 1.0f;
  n.cos_e = 0.0f;
  n.flags = double_sided ? EMITTER_TWO_SIDED : 0u;
  n.entry = LIGHT_NONE;
  return n;
}
}  // namespace

const char* light_sampler_names() { return "uniform, power, tree, slc"; }

const char* light_sampler_name(LightSamplerKind kind) {
  switch (kind) {
    case LightSamplerKind::Uniform: return "uniform";
    case LightSamplerKind::Power: return "power";
    case LightSamplerKind::Tree: return "tree";
    case LightSamplerKind::Slc: return "slc";
  }
  return "power";
}

LightSamplerKind parse_light_sampler(const std::string& name) {
  for (LightSamplerKind k : {LightSamplerKind::Uniform, LightSamplerKind::Power, LightSamplerKind::Tree, LightSamplerKind::Slc})
    if (name == light_sampler_name(k)) return k;
  throw Error("unknown light sampler '" + name + "' (valid: " + light_sampler_names() + ")");
}

size_t PackedLights::bytes() const {
  return sizeof header + punctual.size() * sizeof(glsl::LightPunctual) +
         distribution.size() * sizeof(glsl::LightCdfEntry) + emissive.size() * sizeof(glsl::LightEmissive) +
         light_of_triangle.size() * sizeof(uint32_t) + tree.size() * sizeof(glsl::EmitterNode);
}

LightSampler::LightSampler(const Scene& scene, LightSamplerKind kind, EmitterTreeBuild build, EmitterDistance distance)
    : scene_(&scene), kind_(kind) {
  const bool tree = kind == LightSamplerKind::Tree || kind == LightSamplerKind::Slc;
  // Per material: the luminance of its mean emitted radiance, and the power per unit area.
  std::vector<float> material_radiance(scene.materials.size(), 0.0f);
  std::vector<float> material_scale(scene.materials.size(), 0.0f);
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mat = scene.materials[m];
    float tex = mat.emissive_texture >= 0 && size_t(mat.emissive_texture) < scene.textures.size()
                    ? mean_luminance(scene.textures[mat.emissive_texture])
                    : 1.0f;
    material_radiance[m] = luminance(mat.emission) * tex;
    material_scale[m] = material_radiance[m] * kPi * (mat.double_sided ? 2.0f : 1.0f);
  }
  // Emissive triangles take consecutive entries after the punctual lights, in triangle order:
  // each triangle's area (0: no light) in parallel, their ranks in one serial pass, then every
  // entry in parallel. Large scenes spend their light setup here.
  const size_t triangle_count = scene.triangles.size();
  UninitializedVector<float> area(triangle_count);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, triangle_count, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t != r.end(); ++t) {
      float a = material_scale[scene.triangle_material[t]] > 0.0f ? triangle_area(scene, uint32_t(t)) : 0.0f;
      area[t] = a > 0.0f ? a : 0.0f;
    }
  });
  const uint32_t punctual_count = uint32_t(scene.lights.size());
  packed_.light_of_triangle.reserve(triangle_count);
  for (size_t t = 0; t < triangle_count; ++t) {
    if (!(area[t] > 0.0f)) {
      packed_.light_of_triangle.push_back(LIGHT_NONE);
      continue;
    }
    packed_.light_of_triangle.push_back(punctual_count + uint32_t(packed_.emissive.size()));
    packed_.emissive.push_back({uint32_t(t), area[t]});
  }
  const size_t emissive_count = packed_.emissive.size();
  std::vector<double> weights(punctual_count + emissive_count);
  UninitializedVector<glsl::EmitterNode> leaves;
  if (tree) resize_uninitialized(leaves, weights.size(), /*huge_pages=*/true);
  for (uint32_t i = 0; i < punctual_count; ++i) {
    weights[i] = punctual_power(scene.lights[i], scene.bounds);
    if (tree) leaves[i] = punctual_leaf(scene.lights[i]);
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, emissive_count, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k) {
      const glsl::LightEmissive& e = packed_.emissive[k];
      uint32_t m = scene.triangle_material[e.triangle];
      weights[punctual_count + k] = double(e.area) * material_scale[m];
      if (tree)
        leaves[punctual_count + k] =
            triangle_leaf(scene, e.triangle, material_radiance[m], scene.materials[m].double_sided, e.area);
    }
  });
  distribution_ = DiscreteDistribution(weights);

  glsl::LightHeader& h = packed_.header;
  h.punctual_count = uint32_t(scene.lights.size());
  h.emissive_count = uint32_t(packed_.emissive.size());
  // An empty distribution picks nothing: the sampling tests distribution_size == 0.
  h.distribution_size = distribution_.empty() ? 0u : uint32_t(distribution_.size());
  h.triangle_count = uint32_t(scene.triangles.size());
  h.bounds_center = scene.bounds.center();
  h.bounds_radius = 0.5f * scene.bounds.diagonal();
  h.sampler_kind = uint32_t(kind);
  h.tree_distance = uint32_t(distance);
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
  if (tree && !distribution_.empty()) {
    EmitterTree built = build_emitter_tree(leaves, build);
    h.tree_leaves = built.leaves;
    h.directional_count = built.directional_count;
    for (size_t i = 0; i < packed_.distribution.size(); ++i) packed_.distribution[i].tree_node = built.node_of_entry[i];
    packed_.tree = std::move(built.nodes);
  }
}

}  // namespace sst
