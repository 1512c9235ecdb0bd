#include "core/scene/default_scene.h"

#include <gtest/gtest.h>

#include "core/scene/gltf_loader.h"
#include "tests/test_util.h"

namespace sst {
namespace {

TEST(DefaultScene, IsTheCornellBox) {
  Scene s = load_default_scene();
  EXPECT_EQ(s.source, "builtin:cornell-box");
  EXPECT_EQ(s.triangles.size(), 36u);
  EXPECT_EQ(s.triangle_material.size(), 36u);
  EXPECT_TRUE(s.lights.empty());
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].name, "main");
  EXPECT_NEAR(s.cameras[0].eye.z, 3.9f, 1e-6f);
  int emissive = 0;
  for (size_t m = 0; m < s.materials.size(); ++m) {
    if (!s.material_emits(uint32_t(m))) continue;
    ++emissive;
    EXPECT_NEAR(s.materials[m].emission.x, 17.0f, 1e-4f);
    EXPECT_NEAR(s.materials[m].emission.y, 12.0f, 1e-4f);
    EXPECT_NEAR(s.materials[m].emission.z, 4.0f, 1e-4f);
  }
  EXPECT_EQ(emissive, 1);
  for (const Material& m : s.materials) EXPECT_TRUE(m.double_sided);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
}

TEST(DefaultScene, EqualsTheSharedReferenceScene) {
  auto path = test::shared_scene("cornell-box/cornell-box.gltf");
  if (path.empty()) GTEST_SKIP() << "shared scenes not present";
  Scene a = load_default_scene();
  Scene b = load_gltf(path.string());
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.triangle_material, b.triangle_material);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].base_color, b.materials[i].base_color);
    EXPECT_EQ(a.materials[i].emission, b.materials[i].emission);
  }
}

}  // namespace
}  // namespace sst
