// The lights on the GPU: a LightSampler's tables (core/lights/light_sampler.h) packed into the
// std430 arrays of core/lights/light_layout.h (pack_lights: plain C++, no device needed) and
// uploaded into storage buffers (GpuLights), which gpu/shaders/light_sampler.glsl reads to sample
// exactly what LightSampler samples. The twin of gpu/scene_upload.h for the lights.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"
#include "core/lights/light_layout.h"

namespace sst::gpu {

// The light tables in GPU layout, index for index with the LightSampler they came from.
struct PackedLights {
  glsl::LightHeader header{};
  std::vector<glsl::LightPunctual> punctual;       // Scene::lights
  std::vector<glsl::LightCdfEntry> distribution;   // LightSampler's distribution (empty if it is)
  std::vector<glsl::LightEmissive> emissive;       // LightSampler's emissive triangles
  std::vector<uint32_t> light_of_triangle;         // per scene triangle; LIGHT_NONE if no light

  size_t bytes() const;
};

// Packs `lights`, which must have been built from `scene`. Throws sst::Error when the counts
// disagree (a sampler of another scene).
PackedLights pack_lights(const Scene& scene, const LightSampler& lights);

}  // namespace sst::gpu

#ifdef SST_HAVE_VULKAN
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// The packed lights in five storage buffers, bound in the order of buffers() (the order of
// LIGHT_BUFFERS(first) in GLSL: header, punctual, distribution, emissive, light_of_triangle).
class GpuLights {
 public:
  static constexpr uint32_t kBufferCount = LIGHT_BUFFER_COUNT;

  GpuLights(const VulkanContext& context, const Scene& scene, const LightSampler& lights);
  GpuLights(const VulkanContext& context, const PackedLights& packed);
  GpuLights(const GpuLights&) = delete;
  GpuLights& operator=(const GpuLights&) = delete;

  // Bindings first .. first + 4 of a shader that declares LIGHT_BUFFERS(first).
  std::vector<const GpuBuffer*> buffers() const;
  const glsl::LightHeader& header() const { return header_; }
  size_t bytes() const;

 private:
  glsl::LightHeader header_;
  std::unique_ptr<GpuBuffer> header_buffer_, punctual_, distribution_, emissive_, light_of_triangle_;
};

}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
