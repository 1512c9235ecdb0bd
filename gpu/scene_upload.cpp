// sst_gpu is built without sst_core's compile definitions; keep glm's types declared as they are
// everywhere else in the tool.
#ifndef GLM_FORCE_XYZW_ONLY
#define GLM_FORCE_XYZW_ONLY 1
#endif
#include "gpu/scene_upload.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>

#include "core/scene/scene_access.h"
#include "core/util/error.h"

namespace sst::gpu {
namespace {

std::string megabytes(size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", double(bytes) / 1e6);
  return text;
}

}  // namespace

size_t PackedScene::bytes() const {
  return vertices.size() * sizeof(glsl::SceneVertex) + triangles.size() * sizeof(glsl::SceneTriangle) +
         materials.size() * sizeof(glsl::SceneMaterial) + textures.size() * sizeof(glsl::SceneTexture) +
         texels.size() * sizeof(uint32_t);
}

PackedScene pack_scene(const Scene& scene) {
  const std::string where = "scene " + scene.source + ": ";
  const size_t n = scene.positions.size();
  if (scene.normals.size() != n)
    throw Error(where + std::to_string(scene.normals.size()) + " normals for " + std::to_string(n) + " vertices");
  if (!scene.uvs.empty() && scene.uvs.size() != n)
    throw Error(where + std::to_string(scene.uvs.size()) + " uvs for " + std::to_string(n) + " vertices");
  if (!scene.tangents.empty() && scene.tangents.size() != n)
    throw Error(where + std::to_string(scene.tangents.size()) + " tangents for " + std::to_string(n) + " vertices");
  if (!scene.colors.empty() && scene.colors.size() != n)
    throw Error(where + std::to_string(scene.colors.size()) + " colors for " + std::to_string(n) + " vertices");
  if (scene.triangle_material.size() != scene.triangles.size())
    throw Error(where + std::to_string(scene.triangle_material.size()) + " triangle materials for " +
                std::to_string(scene.triangles.size()) + " triangles");
  if (n > std::numeric_limits<uint32_t>::max()) throw Error(where + "more than 2^32 vertices");

  PackedScene out;
  out.vertices.resize(n);
  for (size_t i = 0; i < n; ++i) {
    glsl::SceneVertex& v = out.vertices[i];
    v.position = scene.positions[i];
    v.normal = scene.normals[i];
    const vec2 uv = scene_uv(scene, uint32_t(i));
    v.u = uv.x;
    v.v = uv.y;
    v.tangent = scene_tangent(scene, uint32_t(i));
    v.color = scene_color(scene, uint32_t(i));
  }

  out.triangles.resize(scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const uvec3& t = scene.triangles[i];
    const uint32_t m = scene.triangle_material[i];
    if (t.x >= n || t.y >= n || t.z >= n)
      throw Error(where + "triangle " + std::to_string(i) + " names a vertex beyond the " + std::to_string(n));
    if (m >= scene.materials.size())
      throw Error(where + "triangle " + std::to_string(i) + " names material " + std::to_string(m) + " of " +
                  std::to_string(scene.materials.size()));
    out.triangles[i] = scene_triangle(scene, uint32_t(i));
  }

  const size_t texture_count = scene.textures.size();
  out.materials.resize(scene.materials.size());
  for (size_t i = 0; i < scene.materials.size(); ++i) out.materials[i] = scene_material(scene, uint32_t(i));

  // Texel storage first, so that the texel array is allocated once.
  size_t words = SCENE_TEXELS_FIRST_TEXEL;
  for (size_t i = 0; i < texture_count; ++i) {
    const Texture& t = scene.textures[i];
    const size_t count = t.width > 0 && t.height > 0 ? t.texel_count() : 0;
    const bool is_float = !t.texels.empty();  // Texture::texel prefers float texels
    const size_t have = is_float ? t.texels.size() : t.rgba8.size();
    if (have < count)
      throw Error(where + "texture " + std::to_string(i) + " has " + std::to_string(have) + " texels for " +
                  std::to_string(t.width) + " x " + std::to_string(t.height));
    words += is_float ? 4 * count : count;
  }
  if (words > std::numeric_limits<uint32_t>::max())
    throw Error(where + "textures of " + megabytes(4 * words) + " exceed 32-bit texel offsets");
  out.texels.reserve(words);
  out.texels.insert(out.texels.end(), std::begin(glsl::scene_texel_tables), std::end(glsl::scene_texel_tables));
  out.textures.resize(texture_count);
  for (size_t i = 0; i < texture_count; ++i) {
    const Texture& t = scene.textures[i];
    const size_t count = t.width > 0 && t.height > 0 ? t.texel_count() : 0;
    glsl::SceneTexture& g = out.textures[i];
    g = texture_layout(t);
    g.texel_offset = uint32_t(out.texels.size());
    if (g.format == SCENE_TEXTURE_RGBA32F) {
      const size_t first = out.texels.size();
      out.texels.resize(first + 4 * count);
      std::memcpy(out.texels.data() + first, t.texels.data(), 4 * count * sizeof(float));
    } else {
      out.texels.insert(out.texels.end(), t.rgba8.begin(), t.rgba8.begin() + std::ptrdiff_t(count));
    }
  }
  return out;
}

std::string describe(const PackedScene& packed) {
  int max_side = 0;
  for (const glsl::SceneTexture& t : packed.textures) max_side = std::max({max_side, t.width, t.height});
  std::string text = "scene on the GPU: " + std::to_string(packed.vertices.size()) + " vertices, " +
                     std::to_string(packed.triangles.size()) + " triangles, " +
                     std::to_string(packed.materials.size()) + " materials, " +
                     std::to_string(packed.textures.size()) + " textures";
  if (!packed.textures.empty()) text += " (largest side " + std::to_string(max_side) + ")";
  return text + ", " + megabytes(packed.bytes());
}

#ifdef SST_HAVE_VULKAN

GpuScene::GpuScene(const VulkanContext& context, const Scene& scene) : GpuScene(context, pack_scene(scene)) {}

GpuScene::GpuScene(const VulkanContext& context, const PackedScene& packed)
    : vertices_(upload_buffer(context, packed.vertices, "scene vertices")),
      triangles_(upload_buffer(context, packed.triangles, "scene triangles")),
      materials_(upload_buffer(context, packed.materials, "scene materials")),
      textures_(upload_buffer(context, packed.textures, "scene textures")),
      texels_(upload_buffer(context, packed.texels, "scene texels")),
      vertex_count_(packed.vertices.size()),
      triangle_count_(packed.triangles.size()),
      material_count_(packed.materials.size()),
      texture_count_(packed.textures.size()),
      texel_words_(packed.texels.size()) {}

std::vector<const GpuBuffer*> GpuScene::buffers() const {
  return {vertices_.get(), triangles_.get(), materials_.get(), textures_.get(), texels_.get()};
}

size_t GpuScene::bytes() const {
  return vertices_->size() + triangles_->size() + materials_->size() + textures_->size() + texels_->size();
}
#endif  // SST_HAVE_VULKAN

}  // namespace sst::gpu
