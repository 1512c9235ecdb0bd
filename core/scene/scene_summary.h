// What a scene contains and what it requires from the renderer: written into every JSON
// record, and used to model only what the scene needs, and to say so in the record.
#pragma once
#include <nlohmann/json.hpp>

#include "core/scene/scene.h"

namespace sst {

// Which light types and material models the scene needs. Only materials that some triangle
// uses count.
struct SceneRequirements {
  bool point_lights = false;
  bool spot_lights = false;
  bool directional_lights = false;
  bool emissive_triangles = false;
  // A used material with metallic > 0 or roughness < 1 anywhere on its surface (a
  // metallicRoughness texture counts by its extreme texels). Always false under diffuse_only.
  bool glossy = false;
  // A used material samples a texture (the metallicRoughness one only when not diffuse_only).
  bool textures = false;
};

SceneRequirements requirements(const Scene& scene, bool diffuse_only);
nlohmann::json to_json(const SceneRequirements& r);

// source, counts, light counts by type, emissive triangles, bounds, camera names, requires,
// warnings, and for an animated scene its animation's summary.
nlohmann::json scene_summary(const Scene& scene, bool diffuse_only);

}  // namespace sst
