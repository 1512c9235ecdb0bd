// The SCENE_* hooks of the shared scene kernels (core/shading/surface_eval.h, and through it
// core/lights/light_sample.h) bound to a sst::Scene on the CPU, and the conversions from the
// Scene's own arrays to the layout structs of core/scene/scene_layout.h that the hooks return (the
// GPU's pack_scene packs with the same conversions). The kernels read the Scene's arrays in place:
// nothing is copied per scene.
#pragma once
#include <cstdint>

#include "core/scene/scene.h"
#include "core/scene/scene_layout.h"

namespace sst {

// Triangle t's vertex indices and material.
inline SceneTriangle scene_triangle(const Scene& scene, uint32_t t) {
  const uvec3& v = scene.triangles[t];
  SceneTriangle out;
  out.v0 = v.x;
  out.v1 = v.y;
  out.v2 = v.z;
  out.material = scene.triangle_material[t];
  return out;
}

inline vec2 scene_uv(const Scene& scene, uint32_t i) { return scene.uvs.empty() ? vec2(0.0f) : scene.uvs[i]; }

// A texture index of a material as the kernels take it: -1 for none and for an index beyond the
// texture table (sampled as 1, like an absent texture).
inline int scene_texture_index(const Scene& scene, int index) {
  return index >= 0 && size_t(index) < scene.textures.size() ? index : -1;
}

// Material m in the kernels' layout.
inline SceneMaterial scene_material(const Scene& scene, uint32_t m) {
  const Material& mat = scene.materials[m];
  SceneMaterial out;
  out.base_color = mat.base_color;
  out.metallic = mat.metallic;
  out.emission = mat.emission;
  out.roughness = mat.roughness;
  out.base_color_texture = scene_texture_index(scene, mat.base_color_texture);
  out.metallic_roughness_texture = scene_texture_index(scene, mat.metallic_roughness_texture);
  out.emissive_texture = scene_texture_index(scene, mat.emissive_texture);
  out.double_sided = mat.double_sided ? 1u : 0u;
  return out;
}

}  // namespace sst

#define SCENE_CTX_PARAM const ::sst::Scene &scene,
#define SCENE_CTX scene,
#define SCENE_TRIANGLE(t) ::sst::scene_triangle(scene, t)
#define SCENE_POSITION(i) scene.positions[i]
#define SCENE_NORMAL(i) scene.normals[i]
#define SCENE_UV(i) ::sst::scene_uv(scene, i)
#define SCENE_MATERIAL(m) ::sst::scene_material(scene, m)
#define SCENE_TEXTURE_SAMPLE(k, uv) scene.textures[k].sample(uv)
