// The scene every backend renders: one triangle soup in world space (all node transforms
// baked), materials, textures, punctual lights and cameras. Built by the glTF loader or in code
// (analytic test scenes); nothing downstream knows about glTF.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/math/math.h"
#include "core/scene/texture.h"

namespace sst {

// How a material's alpha decides which hits count (glTF alphaMode).
enum class AlphaMode {
  Opaque,  // every hit counts
  Mask,    // a hit counts where alpha >= alpha_cutoff
  Blend,   // rendered as Mask with cutoff 0.5: a cutout, not partial transparency (docs/sst-render.md, glTF features)
};

// glTF metallic-roughness material. Texture indices are -1 when absent.
struct Material {
  std::string name;
  vec3 base_color{1.0f};  // linear RGB factor
  int base_color_texture = -1;
  float metallic = 1.0f;
  float roughness = 1.0f;
  int metallic_roughness_texture = -1;  // glTF: G = roughness, B = metallic (linear)
  vec3 emission{0.0f};  // emissiveFactor * KHR_materials_emissive_strength (radiance)
  int emissive_texture = -1;
  bool double_sided = false;
  float alpha = 1.0f;  // baseColorFactor's alpha; the base-colour texture's and COLOR_0's multiply it
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;  // Mask only
  int normal_texture = -1;    // tangent-space normal map (linear)
  float normal_scale = 1.0f;  // scales the map's x and y
};

enum class LightType { Point, Spot, Directional };

// KHR_lights_punctual, radiometric: point/spot intensity in W/sr, directional in W/m^2.
struct PunctualLight {
  std::string name;
  LightType type = LightType::Point;
  vec3 position{0.0f};
  vec3 direction{0.0f, 0.0f, -1.0f};  // unit; the direction the light travels (spot, directional)
  vec3 intensity{1.0f};               // color * intensity
  float cos_inner = 1.0f;             // spot cone cosines (glTF inner/outer cone angles)
  float cos_outer = 0.0f;
};

struct Camera {
  std::string name;
  vec3 eye{0.0f};
  vec3 forward{0.0f, 0.0f, -1.0f};  // unit
  vec3 up{0.0f, 1.0f, 0.0f};        // unit, orthogonal to forward
  float yfov = 0.8f;                // vertical field of view, radians
  float aspect = 0.0f;              // width / height; 0 when the file gives none
};

class SceneAnimation;

struct Scene {
  std::string source;  // file path, or "builtin:<name>" / "generated:<name>"

  // Geometry: indexed triangles; normals and uvs are per vertex (uvs zero when absent).
  std::vector<vec3> positions;
  std::vector<vec3> normals;
  std::vector<vec2> uvs;
  // Per vertex, or empty when no primitive has them: glTF TANGENT (unit xyz, bitangent sign w; zero
  // where a primitive has none: the kernels then derive a tangent from the triangle's uvs) and
  // COLOR_0 (linear RGBA; 1 where a primitive has none).
  std::vector<vec4> tangents;
  std::vector<vec4> colors;
  std::vector<uvec3> triangles;
  std::vector<uint32_t> triangle_material;  // index into materials, one per triangle

  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<PunctualLight> lights;
  std::vector<Camera> cameras;

  Bounds3 bounds;  // of all vertices
  std::vector<std::string> warnings;  // non-fatal loader findings, reported in the JSON record
  // glTF features beyond the core that the file uses and sst models ("KHR_texture_transform",
  // "TEXCOORD_1", "KHR_mesh_quantization"), sorted: results say what the scene required.
  std::vector<std::string> gltf_features;

  // Poses this scene at a time (core/scene/animation.h); null when nothing in it moves.
  std::shared_ptr<const SceneAnimation> animation;

  // Recomputes bounds; the loader and code-built scenes call it once geometry is final.
  void finalize_bounds();
  bool material_emits(uint32_t m) const;
  // The index of the camera (or punctual light) named `name_or_index`, matched by name first,
  // then as a decimal index; -1 when there is none. "" is the first camera.
  int find_camera(const std::string& name_or_index) const;
  int find_light(const std::string& name_or_index) const;
};

// A copy of `scene` in which only its emitters show: every material's base colour black (no
// texture, not metallic), no punctual lights. Rendered diffuse-only, a pixel is non-zero exactly
// where an emitter is seen directly: the mask of the pixels that visible emitters touch, which
// light-sampler comparisons leave out (sst-render --emitters-only, sweeps' reference "mask").
Scene emitters_only(const Scene& scene);

// The largest coordinate magnitude a scene may hold. Beyond it float has no useful resolution
// (its spacing at 1e12 is 2^16 units), squared distances approach float's range, and near 1.8e18
// Embree's BVH build asserts. Checked before anything is built or any ray traced.
constexpr float kMaxCoordinate = 1e12f;
// Throws sst::Error naming the scene's source when a vertex or punctual light lies beyond
// kMaxCoordinate (or is not finite); the bounds must be finalized.
void check_coordinates(const Scene& scene);
// The same for a camera's position.
void check_coordinates(const Camera& camera, const std::string& source);

}  // namespace sst
