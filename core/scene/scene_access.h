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
inline vec4 scene_tangent(const Scene& scene, uint32_t i) { return scene.tangents.empty() ? vec4(0.0f) : scene.tangents[i]; }
inline vec4 scene_color(const Scene& scene, uint32_t i) { return scene.colors.empty() ? vec4(1.0f) : scene.colors[i]; }

// The cutoff of SceneMaterial::alpha_cutoff: 0 for an opaque material (every hit counts).
inline float material_alpha_cutoff(const Material& m) {
  switch (m.alpha_mode) {
    case AlphaMode::Mask: return m.alpha_cutoff;
    case AlphaMode::Blend: return 0.5f;
    default: return 0.0f;
  }
}

// A texture index of a material as the kernels take it: -1 for none and for an index beyond the
// texture table (sampled as 1, like an absent texture).
inline int scene_texture_index(const Scene& scene, int index) {
  return index >= 0 && size_t(index) < scene.textures.size() ? index : -1;
}

// Whether triangle t's material has an alpha test (a scene built in code may name no material).
inline bool triangle_alpha_tested(const Scene& scene, uint32_t t) {
  const uint32_t m = t < scene.triangle_material.size() ? scene.triangle_material[t] : UINT32_MAX;
  return m < scene.materials.size() && material_alpha_cutoff(scene.materials[m]) > 0.0f;
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
  out.alpha = mat.alpha;
  out.alpha_cutoff = material_alpha_cutoff(mat);
  out.normal_texture = scene_texture_index(scene, mat.normal_texture);
  out.normal_scale = mat.normal_scale;
  return out;
}

}  // namespace sst

#define SCENE_CTX_PARAM const ::sst::Scene &scene,
#define SCENE_CTX scene,
#define SCENE_TRIANGLE(t) ::sst::scene_triangle(scene, t)
#define SCENE_POSITION(i) scene.positions[i]
#define SCENE_NORMAL(i) scene.normals[i]
#define SCENE_UV(i) ::sst::scene_uv(scene, i)
#define SCENE_TANGENT(i) ::sst::scene_tangent(scene, i)
#define SCENE_COLOR(i) ::sst::scene_color(scene, i)
#define SCENE_MATERIAL(m) ::sst::scene_material(scene, m)
#define SCENE_TEXTURE_SAMPLE(k, uv) scene.textures[k].sample(uv)
