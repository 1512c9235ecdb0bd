#include "core/scene/scene_summary.h"

#include <gtest/gtest.h>

#include "core/scene/default_scene.h"

namespace sst {
namespace {

// One triangle with one material, built in code.
Scene one_triangle(const Material& m) {
  Scene s;
  s.source = "generated:triangle";
  s.positions = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
  s.normals.assign(3, vec3(0, 0, 1));
  s.uvs.assign(3, vec2(0));
  s.triangles = {uvec3(0, 1, 2)};
  s.triangle_material = {0};
  s.materials = {m};
  s.finalize_bounds();
  return s;
}

Material lambert() {
  Material m;
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  return m;
}

TEST(SceneSummary, DefaultSceneSummary) {
  Scene s = load_default_scene();
  nlohmann::json j = scene_summary(s, true);
  EXPECT_EQ(j["source"], "builtin:cornell-box");
  EXPECT_EQ(j["triangles"], 36);
  EXPECT_EQ(j["vertices"], s.positions.size());
  EXPECT_EQ(j["materials"], s.materials.size());
  EXPECT_EQ(j["textures"], 0);
  EXPECT_EQ(j["lights"]["point"], 0);
  EXPECT_EQ(j["emissive_triangles"], 2);
  EXPECT_EQ(j["cameras"], nlohmann::json::array({"main"}));
  EXPECT_NEAR(j["bounds"]["diagonal"].get<double>(), s.bounds.diagonal(), 1e-6);
  EXPECT_EQ(j["bounds"]["min"].size(), 3u);
  EXPECT_TRUE(j["requires"]["emissive_triangles"]);
  EXPECT_FALSE(j["requires"]["glossy"]);  // diffuse_only
  EXPECT_FALSE(j["requires"]["point_lights"]);
  EXPECT_TRUE(j["warnings"].is_array());
  // The Cornell box's materials have roughness 0: glossy unless rendered diffuse-only.
  EXPECT_TRUE(requirements(s, false).glossy);
}

TEST(SceneSummary, CountsLightsByType) {
  Scene s = one_triangle(lambert());
  PunctualLight p, spot, sun;
  spot.type = LightType::Spot;
  sun.type = LightType::Directional;
  s.lights = {p, p, spot, sun};
  nlohmann::json j = scene_summary(s, false);
  EXPECT_EQ(j["lights"]["point"], 2);
  EXPECT_EQ(j["lights"]["spot"], 1);
  EXPECT_EQ(j["lights"]["directional"], 1);
  SceneRequirements r = requirements(s, false);
  EXPECT_TRUE(r.point_lights && r.spot_lights && r.directional_lights);
  EXPECT_FALSE(r.emissive_triangles || r.glossy || r.textures);
}

TEST(SceneSummary, GlossyFollowsFactorsAndTheMetallicRoughnessTexture) {
  Material m = lambert();
  EXPECT_FALSE(requirements(one_triangle(m), false).glossy);
  m.roughness = 0.5f;
  EXPECT_TRUE(requirements(one_triangle(m), false).glossy);
  EXPECT_FALSE(requirements(one_triangle(m), true).glossy);

  // Factors metallic 1, roughness 1 scaled by a texture: glossy iff some texel has B > 0 or G < 1.
  Material textured;
  textured.metallic_roughness_texture = 0;
  Texture rough_dielectric;
  rough_dielectric.width = 2;
  rough_dielectric.height = 1;
  rough_dielectric.texels = {vec4(0, 1, 0, 1), vec4(0, 1, 0, 1)};
  Scene s = one_triangle(textured);
  s.textures = {rough_dielectric};
  EXPECT_FALSE(requirements(s, false).glossy);
  EXPECT_FALSE(requirements(s, true).textures);  // only the metallicRoughness texture
  EXPECT_TRUE(requirements(s, false).textures);
  s.textures[0].texels[1] = vec4(0, 1, 0.2f, 1);
  EXPECT_TRUE(requirements(s, false).glossy);
}

TEST(SceneSummary, UnusedMaterialsDoNotCount) {
  Scene s = one_triangle(lambert());
  Material glossy_lamp;
  glossy_lamp.roughness = 0.1f;
  glossy_lamp.emission = vec3(5.0f);
  glossy_lamp.base_color_texture = 0;
  s.materials.push_back(glossy_lamp);
  s.textures.resize(1);
  SceneRequirements r = requirements(s, false);
  EXPECT_FALSE(r.glossy || r.emissive_triangles || r.textures);
}

}  // namespace
}  // namespace sst
