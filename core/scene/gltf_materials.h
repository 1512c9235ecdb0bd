// glTF materials as sst Materials: factors checked and clamped, alpha modes, the textures a used
// material samples (as TextureKeys for gltf_textures.h to decode), and the UV set and
// KHR_texture_transform that each material's vertices are loaded with. Apart from the loader,
// which asks only for a material's UV mapping while it loads meshes and for the materials once
// it knows which of them triangles use.
#pragma once
#include <array>
#include <map>
#include <vector>

#include "core/scene/gltf_context.h"
#include "core/scene/gltf_textures.h"
#include "core/scene/scene.h"

namespace sst::gltf {

// The UVs a material's textures are sampled at: TEXCOORD_<set>, mapped by the affine transform
// u' = u[0] u + u[1] v + u[2], v' = v[0] u + v[1] v + v[2] (KHR_texture_transform).
constexpr int kMaxUvSet = 7;
struct UvMapping {
  int set = 0;
  std::array<double, 3> u{1.0, 0.0, 0.0};
  std::array<double, 3> v{0.0, 1.0, 0.0};
  bool operator==(const UvMapping&) const = default;
  bool affine_identity() const { return u == UvMapping{}.u && v == UvMapping{}.v; }
  std::vector<float> apply(const std::vector<float>& uvs) const {
    std::vector<float> out(uvs.size());
    for (size_t i = 0; i + 1 < uvs.size(); i += 2) {
      out[i] = float(u[0] * uvs[i] + u[1] * uvs[i + 1] + u[2]);
      out[i + 1] = float(v[0] * uvs[i] + v[1] * uvs[i + 1] + v[2]);
    }
    return out;
  }
};

class Materials {
 public:
  explicit Materials(Context& ctx) : ctx_(ctx) {}

  // One UV mapping per material, applied to its vertices when they are loaded (exact: the
  // transform is affine, so it commutes with the interpolation over a triangle): that of its
  // baseColorTexture, else of its first other texture. Textures of one material that disagree
  // keep the first's, with a warning. -1 (no material) and a missing one map to identity.
  const UvMapping& uv_mapping(int gltf_material);

  // Appends to scene.materials one Material per glTF material, then glTF's default material when
  // a triangle uses it (scene.triangle_material must be final). Unused materials keep their
  // factors but no textures, so that unused images are never read.
  void build(Scene& scene);

  // The textures the built materials index, in slot order.
  const std::vector<TextureKey>& texture_keys() const { return texture_keys_; }

 private:
  Material convert_material(int index, bool used);
  void attach_textures(const tinygltf::Material& g, const std::string& what, Material& out);
  int texture_slot(const tinygltf::TextureInfo& info, bool srgb, const std::string& what);

  Context& ctx_;
  std::map<TextureKey, int> texture_slots_;
  std::vector<TextureKey> texture_keys_;
  std::map<int, UvMapping> uv_mappings_;  // by glTF material
};

}  // namespace sst::gltf
