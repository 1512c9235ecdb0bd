#include "core/scene/scene.h"

namespace sst {
void Scene::finalize_bounds() {
  bounds = Bounds3{};
  for (const vec3& p : positions) bounds.extend(p);
}

bool Scene::material_emits(uint32_t m) const {
  return m < materials.size() && max_component(materials[m].emission) > 0.0f;
}
}  // namespace sst
