#include "tests/analytic_scenes.h"

namespace sst::test {
namespace {
void add_quad(Scene& s, vec3 a, vec3 b, vec3 c, vec3 d, uint32_t material) {
  uint32_t base = uint32_t(s.positions.size());
  vec3 n = glm::normalize(glm::cross(b - a, c - a));
  for (vec3 p : {a, b, c, d}) {
    s.positions.push_back(p);
    s.normals.push_back(n);
    s.uvs.push_back(vec2(0.0f));
  }
  s.triangles.push_back({base, base + 1, base + 2});
  s.triangles.push_back({base, base + 2, base + 3});
  s.triangle_material.push_back(material);
  s.triangle_material.push_back(material);
}
}  // namespace

Scene lambert_plane(float albedo, float half, float camera_height, float yfov) {
  Scene s;
  s.source = "generated:lambert_plane";
  Material m;
  m.name = "lambert";
  m.base_color = vec3(albedo);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.double_sided = true;
  s.materials.push_back(m);
  add_quad(s, {-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}, 0);
  Camera c;
  c.name = "top";
  c.eye = {0, 0, camera_height};
  c.forward = {0, 0, -1};
  c.up = {0, 1, 0};
  c.yfov = yfov;
  c.aspect = 1.0f;
  s.cameras.push_back(c);
  s.finalize_bounds();
  return s;
}

Scene emissive_box(float albedo, float emission, float side) {
  Scene s;
  s.source = "generated:emissive_box";
  Material m;
  m.name = "furnace";
  m.base_color = vec3(albedo);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.emission = vec3(emission);
  m.double_sided = true;
  s.materials.push_back(m);
  float h = 0.5f * side;
  vec3 p[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}};
  add_quad(s, p[0], p[1], p[2], p[3], 0);
  add_quad(s, p[4], p[7], p[6], p[5], 0);
  add_quad(s, p[0], p[4], p[5], p[1], 0);
  add_quad(s, p[3], p[2], p[6], p[7], 0);
  add_quad(s, p[0], p[3], p[7], p[4], 0);
  add_quad(s, p[1], p[5], p[6], p[2], 0);
  Camera c;
  c.name = "inside";
  c.eye = vec3(0.0f);
  c.forward = {0, 0, -1};
  c.up = {0, 1, 0};
  c.yfov = 1.2f;
  c.aspect = 1.0f;
  s.cameras.push_back(c);
  s.finalize_bounds();
  return s;
}

void scale_scene(Scene& scene, float k) {
  for (vec3& p : scene.positions) p *= k;
  for (PunctualLight& l : scene.lights) l.position *= k;
  for (Camera& c : scene.cameras) c.eye *= k;
  scene.finalize_bounds();
}

}  // namespace sst::test
