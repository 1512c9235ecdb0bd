#include "core/scene/scene_summary.h"

#include "core/scene/animation.h"

namespace sst {
namespace {

std::vector<char> used_materials(const Scene& scene) {
  std::vector<char> used(scene.materials.size(), 0);
  for (uint32_t m : scene.triangle_material)
    if (m < used.size()) used[m] = 1;
  return used;
}

const Texture* texture_at(const Scene& scene, int index) {
  return index >= 0 && size_t(index) < scene.textures.size() ? &scene.textures[index] : nullptr;
}

// The factors scale the texture (glTF: G = roughness, B = metallic), so the material is glossy
// somewhere iff factor * max(B) > 0 or factor * min(G) < 1.
bool is_glossy(const Scene& scene, const Material& m) {
  float max_metallic = m.metallic, min_roughness = m.roughness;
  if (const Texture* t = texture_at(scene, m.metallic_roughness_texture)) {
    float max_b = 0.0f, min_g = 1.0f;
    for (size_t i = 0; i < t->texel_count(); ++i) {
      vec4 texel = t->texel(i);
      max_b = std::max(max_b, texel.z);
      min_g = std::min(min_g, texel.y);
    }
    max_metallic *= max_b;
    min_roughness *= min_g;
  }
  return max_metallic > 0.0f || min_roughness < 1.0f;
}

bool uses_texture(const Scene& scene, const Material& m, bool diffuse_only) {
  return texture_at(scene, m.base_color_texture) || texture_at(scene, m.emissive_texture) ||
         (!diffuse_only && texture_at(scene, m.metallic_roughness_texture));
}

nlohmann::json vec_json(vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace

SceneRequirements requirements(const Scene& scene, bool diffuse_only) {
  SceneRequirements r;
  for (const PunctualLight& l : scene.lights) {
    r.point_lights |= l.type == LightType::Point;
    r.spot_lights |= l.type == LightType::Spot;
    r.directional_lights |= l.type == LightType::Directional;
  }
  for (uint32_t m : scene.triangle_material)
    if (scene.material_emits(m)) {
      r.emissive_triangles = true;
      break;
    }
  std::vector<char> used = used_materials(scene);
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    if (!used[i]) continue;
    r.glossy |= !diffuse_only && is_glossy(scene, scene.materials[i]);
    r.textures |= uses_texture(scene, scene.materials[i], diffuse_only);
  }
  return r;
}

nlohmann::json to_json(const SceneRequirements& r) {
  return {{"point_lights", r.point_lights},
          {"spot_lights", r.spot_lights},
          {"directional_lights", r.directional_lights},
          {"emissive_triangles", r.emissive_triangles},
          {"glossy", r.glossy},
          {"textures", r.textures}};
}

nlohmann::json scene_summary(const Scene& scene, bool diffuse_only) {
  size_t counts[3] = {0, 0, 0};
  for (const PunctualLight& l : scene.lights) ++counts[int(l.type)];
  size_t emissive = 0;
  for (uint32_t m : scene.triangle_material) emissive += scene.material_emits(m);
  nlohmann::json cameras = nlohmann::json::array();
  for (const Camera& c : scene.cameras) cameras.push_back(c.name);
  nlohmann::json bounds = scene.bounds.empty()
                              ? nlohmann::json(nullptr)
                              : nlohmann::json{{"min", vec_json(scene.bounds.lo)},
                                               {"max", vec_json(scene.bounds.hi)},
                                               {"diagonal", scene.bounds.diagonal()}};
  nlohmann::json summary = {{"source", scene.source},
                            {"triangles", scene.triangles.size()},
                            {"vertices", scene.positions.size()},
                            {"materials", scene.materials.size()},
                            {"textures", scene.textures.size()},
                            {"lights",
                             {{"point", counts[int(LightType::Point)]},
                              {"spot", counts[int(LightType::Spot)]},
                              {"directional", counts[int(LightType::Directional)]}}},
                            {"emissive_triangles", emissive},
                            {"bounds", bounds},
                            {"cameras", cameras},
                            {"diffuse_only", diffuse_only},
                            {"requires", to_json(requirements(scene, diffuse_only))},
                            {"gltf_features", scene.gltf_features},
                            {"warnings", scene.warnings}};
  if (scene.animation) summary["animation"] = scene.animation->summary();  // static scenes' records stay as they were
  return summary;
}

}  // namespace sst
