#include "core/scene/scene.h"

namespace sst {
void Scene::finalize_bounds() {
  bounds = Bounds3{};
  for (const vec3& p : positions) bounds.extend(p);
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
}  // namespace sst
