// The lights on the GPU: a LightSampler's tables (PackedLights, core/lights/light_sampler.h, in
// the layout of core/lights/light_layout.h) uploaded as they are into storage buffers
// (GpuLights), which gpu/shaders/light_sampler.glsl binds to the shared sampling
// (core/lights/light_sample.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/lights/light_layout.h"
#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"

namespace sst::gpu {

// The tables of `lights`, after checking that they were built from `scene`: throws sst::Error
// when the counts disagree (a sampler of another scene).
const PackedLights& pack_lights(const Scene& scene, const LightSampler& lights);

}  // namespace sst::gpu

#ifdef SST_HAVE_VULKAN
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// The packed lights in six storage buffers, bound in the order of buffers() (the order of
// LIGHT_BUFFERS(first) in GLSL: header, punctual, distribution, emissive, light_of_triangle,
// tree).
class GpuLights {
 public:
  static constexpr uint32_t kBufferCount = LIGHT_BUFFER_COUNT;

  GpuLights(const VulkanContext& context, const Scene& scene, const LightSampler& lights);
  GpuLights(const VulkanContext& context, const PackedLights& packed);
  GpuLights(const GpuLights&) = delete;
  GpuLights& operator=(const GpuLights&) = delete;

  // Bindings first .. first + 5 of a shader that declares LIGHT_BUFFERS(first).
  std::vector<const GpuBuffer*> buffers() const;
  const glsl::LightHeader& header() const { return header_; }
  // The specialization constants (gpu/shaders/specialization_ids.h) of a pipeline that samples
  // these lights: their sampler fixed, the others left to their run-time values.
  std::vector<uint32_t> sampler_specialization() const;
  size_t bytes() const;

 private:
  glsl::LightHeader header_;
  std::unique_ptr<GpuBuffer> header_buffer_, punctual_, distribution_, emissive_, light_of_triangle_, tree_;
};

}  // namespace sst::gpu
#endif  // SST_HAVE_VULKAN
