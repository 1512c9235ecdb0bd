#include "core/scene/scene.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "core/util/error.h"

namespace sst {
void Scene::finalize_bounds() {
  bounds = Bounds3{};
  for (const vec3& p : positions) bounds.extend(p);
}

Scene emitters_only(const Scene& scene) {
  Scene out = scene;
  for (Material& m : out.materials) {
    m.base_color = vec3(0.0f);
    m.base_color_texture = -1;
    m.metallic = 0.0f;
    m.metallic_roughness_texture = -1;
  }
  out.lights.clear();
  return out;
}

bool Scene::material_emits(uint32_t m) const {
  return m < materials.size() && max_component(materials[m].emission) > 0.0f;
}

namespace {
template <class T>
int find_by_name_or_index(const std::vector<T>& items, const std::string& name_or_index) {
  for (size_t i = 0; i < items.size(); ++i)
    if (items[i].name == name_or_index) return int(i);
  bool numeric = !name_or_index.empty() && name_or_index.size() < 10 &&
                 name_or_index.find_first_not_of("0123456789") == std::string::npos;
  if (numeric && std::stoul(name_or_index) < items.size()) return int(std::stoul(name_or_index));
  return -1;
}
}  // namespace

int Scene::find_camera(const std::string& name_or_index) const {
  if (name_or_index.empty()) return cameras.empty() ? -1 : 0;
  return find_by_name_or_index(cameras, name_or_index);
}

int Scene::find_light(const std::string& name_or_index) const { return find_by_name_or_index(lights, name_or_index); }
namespace {
bool within_range(vec3 p) {
  for (int i = 0; i < 3; ++i)
    if (!(std::fabs(p[i]) <= kMaxCoordinate)) return false;  // also false for NaN
  return true;
}
std::string coordinate_text(vec3 p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(p.x), double(p.y), double(p.z));
  return text;
}
std::string limit_text() {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(kMaxCoordinate));
  return text;
}
}  // namespace

void check_coordinates(const Scene& scene) {
  if (!scene.positions.empty() && (!within_range(scene.bounds.lo) || !within_range(scene.bounds.hi))) {
    for (size_t i = 0; i < scene.positions.size(); ++i)
      if (!within_range(scene.positions[i]))
        throw Error(scene.source + ": vertex " + std::to_string(i) + " at " + coordinate_text(scene.positions[i]) +
                    " lies beyond the largest coordinate float can resolve usefully (" + limit_text() + ")");
  }
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (!within_range(scene.lights[i].position))
      throw Error(scene.source + ": light " + std::to_string(i) + " at " + coordinate_text(scene.lights[i].position) +
                  " lies beyond the largest coordinate float can resolve usefully (" + limit_text() + ")");
}

void check_coordinates(const Camera& camera, const std::string& source) {
  if (!within_range(camera.eye))
    throw Error(source + ": camera" + (camera.name.empty() ? std::string() : " '" + camera.name + "'") + " at " +
                coordinate_text(camera.eye) + " lies beyond the largest coordinate float can resolve usefully (" +
                limit_text() + ")");
}

}  // namespace sst
