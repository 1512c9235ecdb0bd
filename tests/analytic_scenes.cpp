#include "tests/analytic_scenes.h"

#include <algorithm>
#include <cmath>
#include <random>

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
Material diffuse_material(const char* name, float albedo, float emission) {
  Material m;
  m.name = name;
  m.base_color = vec3(albedo);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.emission = vec3(emission);
  m.double_sided = true;
  return m;
}

Camera camera(const char* name, vec3 eye, float yfov) {
  Camera c;
  c.name = name;
  c.eye = eye;
  c.forward = {0, 0, -1};
  c.up = {0, 1, 0};
  c.yfov = yfov;
  c.aspect = 1.0f;
  return c;
}
}  // namespace

Scene lambert_plane(float albedo, float half, float camera_height, float yfov) {
  Scene s;
  s.source = "generated:lambert_plane";
  s.materials.push_back(diffuse_material("lambert", albedo, 0.0f));
  add_quad(s, {-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}, 0);
  s.cameras.push_back(camera("top", {0, 0, camera_height}, yfov));
  s.finalize_bounds();
  return s;
}

namespace {
// The six inward-wound faces of a cube of side `side` centred at the origin, one material.
void add_cube(Scene& s, float side, uint32_t material) {
  float h = 0.5f * side;
  vec3 p[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h}, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h}};
  add_quad(s, p[0], p[1], p[2], p[3], material);
  add_quad(s, p[4], p[7], p[6], p[5], material);
  add_quad(s, p[0], p[4], p[5], p[1], material);
  add_quad(s, p[3], p[2], p[6], p[7], material);
  add_quad(s, p[0], p[3], p[7], p[4], material);
  add_quad(s, p[1], p[5], p[6], p[2], material);
}

// Uniform numbers and directions from one seed, for the generated scenes.
struct Draws {
  std::mt19937 rng;
  explicit Draws(uint32_t seed) : rng(seed) {}
  float uniform(float lo, float hi) { return lo + (hi - lo) * float(rng() >> 8) * 0x1p-24f; }
  vec3 direction() {
    float z = uniform(-1.0f, 1.0f), phi = uniform(0.0f, 6.2831853f), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return vec3(r * std::cos(phi), z, r * std::sin(phi));
  }
};
}  // namespace

Scene emissive_box(float albedo, float emission, float side) {
  Scene s;
  s.source = "generated:emissive_box";
  s.materials.push_back(diffuse_material("furnace", albedo, emission));
  add_cube(s, side, 0);
  s.cameras.push_back(camera("inside", vec3(0.0f), 1.2f));
  s.finalize_bounds();
  return s;
}

Scene diffuse_box(vec3 albedo, float side) {
  Scene s;
  s.source = "generated:diffuse_box";
  Material m = diffuse_material("box", 1.0f, 0.0f);
  m.base_color = albedo;
  s.materials.push_back(m);
  add_cube(s, side, 0);
  s.cameras.push_back(camera("inside", vec3(0.0f), 1.2f));
  s.finalize_bounds();
  return s;
}

Scene diffuse_sphere(float albedo, float radius, int rings) {
  Scene s;
  s.source = "generated:diffuse_sphere";
  s.materials.push_back(diffuse_material("sphere", albedo, 0.0f));
  int segments = 2 * rings;
  for (int i = 0; i <= rings; ++i) {
    double theta = M_PI * double(i) / double(rings);
    for (int j = 0; j <= segments; ++j) {
      double phi = 2.0 * M_PI * double(j) / double(segments);
      vec3 n(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)), float(std::sin(theta) * std::sin(phi)));
      s.positions.push_back(radius * n);
      s.normals.push_back(n);
      s.uvs.push_back(vec2(0.0f));
    }
  }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      uint32_t a = uint32_t(i * (segments + 1) + j), b = a + 1, c = a + uint32_t(segments + 1), d = c + 1;
      if (i > 0) {
        s.triangles.push_back({a, b, d});
        s.triangle_material.push_back(0);
      }
      if (i < rings - 1) {
        s.triangles.push_back({a, d, c});
        s.triangle_material.push_back(0);
      }
    }
  s.cameras.push_back(camera("inside", vec3(0.0f), 1.2f));
  s.finalize_bounds();
  return s;
}

PunctualLight punctual_light(LightType type, vec3 position, vec3 direction, vec3 intensity) {
  PunctualLight l;
  l.name = "light";
  l.type = type;
  l.position = position;
  l.direction = glm::normalize(direction);
  l.intensity = intensity;
  return l;
}

void add_emissive_triangle(Scene& s, vec3 a, vec3 b, vec3 c, vec3 emission, bool double_sided) {
  Material m = diffuse_material("emitter", 0.0f, 0.0f);
  m.emission = emission;
  m.double_sided = double_sided;
  uint32_t material = uint32_t(s.materials.size());
  s.materials.push_back(m);
  uint32_t base = uint32_t(s.positions.size());
  vec3 n = glm::normalize(glm::cross(b - a, c - a));
  for (vec3 p : {a, b, c}) {
    s.positions.push_back(p);
    s.normals.push_back(n);
    s.uvs.push_back(vec2(0.0f));
  }
  s.triangles.push_back({base, base + 1, base + 2});
  s.triangle_material.push_back(material);
  s.finalize_bounds();
}

void scale_scene(Scene& scene, float k) {
  for (vec3& p : scene.positions) p *= k;
  for (PunctualLight& l : scene.lights) l.position *= k;
  for (Camera& c : scene.cameras) c.eye *= k;
  scene.finalize_bounds();
}

Scene many_lights(uint32_t seed, int triangles, int points, int spots, bool sun) {
  Draws draws(seed);
  std::mt19937& rng = draws.rng;
  auto uniform = [&](float lo, float hi) { return draws.uniform(lo, hi); };
  auto direction = [&]() { return draws.direction(); };
  Scene s;
  s.source = "generated:many_lights";
  s.materials.push_back(diffuse_material("floor", 0.5f, 0.0f));
  add_quad(s, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, 0);
  add_quad(s, {-5, 4, -5}, {5, 4, -5}, {5, 4, 5}, {-5, 4, 5}, 0);
  const float radiance[4] = {2.0f, 8.0f, 30.0f, 5.0f};
  const bool two_sided[4] = {false, false, true, true};
  for (int k = 0; k < 4; ++k) {
    Material m = diffuse_material("emitter", 0.0f, radiance[k]);
    m.emission *= vec3(1.0f, 0.5f + 0.15f * float(k), 1.0f - 0.2f * float(k));
    m.double_sided = two_sided[k];
    s.materials.push_back(m);
  }
  for (int i = 0; i < triangles; ++i) {
    vec3 c(uniform(-4.0f, 4.0f), uniform(0.2f, 3.8f), uniform(-4.0f, 4.0f));
    float size = uniform(0.02f, 0.2f);
    vec3 a = c + size * direction(), b = c + size * direction(), d = c + size * direction();
    uint32_t base = uint32_t(s.positions.size());
    vec3 n = glm::cross(b - a, d - a);
    if (!(glm::length(n) > 1e-6f)) continue;
    n = glm::normalize(n);
    for (vec3 p : {a, b, d}) {
      s.positions.push_back(p);
      s.normals.push_back(n);
      s.uvs.push_back(vec2(0.0f));
    }
    s.triangles.push_back({base, base + 1, base + 2});
    s.triangle_material.push_back(1u + uint32_t(rng() % 4u));
  }
  for (int i = 0; i < points + spots; ++i) {
    vec3 pos(uniform(-4.0f, 4.0f), uniform(0.5f, 3.5f), uniform(-4.0f, 4.0f));
    vec3 color = vec3(uniform(0.2f, 1.0f), uniform(0.2f, 1.0f), uniform(0.2f, 1.0f)) * uniform(0.05f, 2.0f);
    if (i < points) {
      s.lights.push_back(punctual_light(LightType::Point, pos, vec3(0, -1, 0), color));
    } else {
      PunctualLight l = punctual_light(LightType::Spot, pos, direction() + vec3(0, -0.7f, 0), color * 4.0f);
      float outer = uniform(0.2f, 1.2f), inner = outer * uniform(0.0f, 0.9f);
      l.cos_outer = std::cos(outer);
      l.cos_inner = std::cos(inner);
      s.lights.push_back(l);
    }
  }
  if (sun) s.lights.push_back(punctual_light(LightType::Directional, vec3(0.0f), vec3(0.3f, -1.0f, 0.2f), vec3(0.4f)));
  s.cameras.push_back(camera("main", {0, 3.5f, 3.5f}, 1.0f));
  s.cameras.back().forward = glm::normalize(vec3(0.0f, -1.0f, -1.0f));
  s.cameras.back().up = glm::normalize(vec3(0.0f, 1.0f, -1.0f));
  s.finalize_bounds();
  return s;
}

Scene light_field(uint32_t seed, int quads, int points, int spots) {
  Draws draws(seed);
  std::mt19937& rng = draws.rng;
  auto uniform = [&](float lo, float hi) { return draws.uniform(lo, hi); };
  auto direction = [&]() { return draws.direction(); };
  Scene s;
  s.source = "generated:light_field";
  s.materials.push_back(diffuse_material("ground", 0.4f, 0.0f));
  add_quad(s, {-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, 0);
  for (int k = 0; k < 32; ++k) {
    Material m = diffuse_material("emitter", 0.0f, 2.0f * std::pow(100.0f, float(k / 4) / 7.0f));
    m.emission *= vec3(1.0f, 0.6f + 0.1f * float(k % 4), 1.0f - 0.15f * float(k % 4));
    m.double_sided = true;
    s.materials.push_back(m);
  }
  for (int i = 0; i < quads; ++i) {
    vec3 c(uniform(-19.5f, 19.5f), uniform(0.3f, 3.0f), uniform(-19.5f, 19.5f));
    vec3 n = direction();
    vec3 u = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? vec3(1, 0, 0) : vec3(0, 1, 0))) * (0.5f * uniform(0.05f, 0.15f));
    vec3 v = glm::cross(n, u);
    add_quad(s, c - u - v, c + u - v, c + u + v, c - u + v, 1u + uint32_t(rng() % 32u));
  }
  for (int i = 0; i < points + spots; ++i) {
    vec3 color = vec3(uniform(0.5f, 1.0f), uniform(0.5f, 1.0f), uniform(0.5f, 1.0f));
    if (i < points) {
      vec3 pos(uniform(-19.0f, 19.0f), uniform(0.5f, 4.0f), uniform(-19.0f, 19.0f));
      s.lights.push_back(punctual_light(LightType::Point, pos, vec3(0, -1, 0), color * std::pow(30.0f, uniform(0.0f, 1.0f))));
    } else {
      vec3 pos(uniform(-18.0f, 18.0f), uniform(3.0f, 6.0f), uniform(-18.0f, 18.0f));
      float tilt = uniform(0.0f, 0.52f), yaw = uniform(0.0f, 6.2831853f);
      vec3 aim(std::sin(tilt) * std::cos(yaw), -std::cos(tilt), std::sin(tilt) * std::sin(yaw));
      PunctualLight l = punctual_light(LightType::Spot, pos, aim, color * 30.0f * std::pow(10.0f, uniform(0.0f, 1.0f)));
      l.cos_inner = std::cos(0.3f);
      l.cos_outer = std::cos(0.6f);
      s.lights.push_back(l);
    }
  }
  s.cameras.push_back(camera("main", {0, 14.0f, 30.0f}, 0.9f));
  s.cameras.back().forward = glm::normalize(vec3(0.0f, -0.47f, -0.88f));
  s.cameras.back().up = glm::normalize(glm::cross(glm::cross(s.cameras.back().forward, vec3(0, 1, 0)), s.cameras.back().forward));
  s.finalize_bounds();
  return s;
}

Scene thin_slats(int slats, float width, float spacing, bool ceiling) {
  Scene s;
  s.source = "generated:thin_slats";
  s.materials.push_back(diffuse_material("diffuse", 0.6f, 0.0f));
  add_quad(s, {-4, 0, 3}, {4, 0, 3}, {4, 0, -3}, {-4, 0, -3}, 0);
  add_quad(s, {-4, 0, -2.5f}, {4, 0, -2.5f}, {4, 3, -2.5f}, {-4, 3, -2.5f}, 0);
  if (ceiling) add_quad(s, {-4, 3, 3}, {-4, 3, -3}, {4, 3, -3}, {4, 3, 3}, 0);
  const float h = 0.5f * width;
  for (int i = 0; i < slats; ++i) {
    float x = spacing * (float(i) - 0.5f * float(slats - 1));
    add_quad(s, {x - h, 0, -1.5f}, {x + h, 0, -1.5f}, {x + h, 2.5f, -1.5f}, {x - h, 2.5f, -1.5f}, 0);
  }
  s.lights.push_back(punctual_light(LightType::Point, vec3(0.0f, 2.5f, 0.5f), vec3(0, -1, 0), vec3(10.0f)));
  Camera c = camera("front", vec3(0.0f, 1.2f, 2.5f), 1.0f);
  c.aspect = 4.0f / 3.0f;
  s.cameras.push_back(c);
  s.finalize_bounds();
  return s;
}

}  // namespace sst::test
