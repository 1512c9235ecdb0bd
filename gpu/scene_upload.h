// The scene on the GPU: a sst::Scene packed into the std430 arrays of core/scene/scene_layout.h
// (pack_scene: plain C++, no device needed, with the conversions the CPU's hooks use,
// core/scene/scene_access.h) and uploaded into storage buffers (GpuScene), to which
// gpu/shaders/surface.glsl binds the shared kernels' hooks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "core/scene/scene_layout.h"

namespace sst::gpu {

// The scene's arrays in GPU layout, index for index: vertices[i] is Scene vertex i, triangles[i]
// Scene triangle i, materials[i] Scene material i, textures[i] Scene texture i; texels holds the
// 8-bit decoding tables (SCENE_TEXELS_FIRST_TEXEL words), then the texels of every texture
// (8-bit: one uint each, as Texture::rgba8; float: four uints each, the bits of Texture::texels),
// in texture order.
struct PackedScene {
  std::vector<glsl::SceneVertex> vertices;
  std::vector<glsl::SceneTriangle> triangles;
  std::vector<glsl::SceneMaterial> materials;
  std::vector<glsl::SceneTexture> textures;
  std::vector<uint32_t> texels;

  // Bytes of all five arrays together (what GpuScene allocates, less the empty-array padding).
  size_t bytes() const;
};

// Packs `scene`. Texture indices beyond the texture table become -1 (sampled as 1, as absent
// textures are). Throws sst::Error (one line naming the triangle, material or
// texture) on what the CPU would read out of bounds: a vertex or material index out of range,
// normals or uvs whose count is not the vertex count, a texture whose texel data is smaller than
// width x height, more texels than 32-bit offsets address.
PackedScene pack_scene(const Scene& scene);

// One line, e.g. "scene on the GPU: 1234 vertices, 2000 triangles, 8 materials, 3 textures
// (2048 x 2048 max), 21.4 MB".
std::string describe(const PackedScene& packed);

}  // namespace sst::gpu

#ifdef SST_HAVE_VULKAN
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// The packed scene in five storage buffers, bound in the order of buffers() (the order of
// SCENE_BUFFERS(first) in GLSL: vertices, triangles, materials, textures, texels). Each buffer is
// checked against the device's storage-buffer limit by GpuBuffer: a scene too large for the device
// is an sst::Error that names the array and its size, never a silent overrun.
class GpuScene {
 public:
  static constexpr uint32_t kBufferCount = 5;

  GpuScene(const VulkanContext& context, const Scene& scene);
  GpuScene(const VulkanContext& context, const PackedScene& packed);
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Bindings first .. first + 4 of a shader that declares SCENE_BUFFERS(first).
  std::vector<const GpuBuffer*> buffers() const;
  const GpuBuffer& vertices() const { return *vertices_; }
  const GpuBuffer& triangles() const { return *triangles_; }
  const GpuBuffer& materials() const { return *materials_; }
  const GpuBuffer& textures() const { return *textures_; }
  const GpuBuffer& texels() const { return *texels_; }

  size_t vertex_count() const { return vertex_count_; }
  size_t triangle_count() const { return triangle_count_; }
  size_t material_count() const { return material_count_; }
  size_t texture_count() const { return texture_count_; }
  size_t texel_words() const { return texel_words_; }
  // Device memory of the five buffers together, in bytes (as allocated: empty arrays take 16).
  size_t bytes() const;

 private:
  std::unique_ptr<GpuBuffer> vertices_, triangles_, materials_, textures_, texels_;
  size_t vertex_count_ = 0, triangle_count_ = 0, material_count_ = 0, texture_count_ = 0, texel_words_ = 0;
};

}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
