// sst_gpu is built without sst_core's compile definitions; keep glm's types declared as they are
// everywhere else in the tool.
#ifndef GLM_FORCE_XYZW_ONLY
#define GLM_FORCE_XYZW_ONLY 1
#endif
#include "gpu/light_upload.h"

#include "core/util/error.h"
#include "gpu/shaders/specialization_ids.h"

namespace sst::gpu {

const PackedLights& pack_lights(const Scene& scene, const LightSampler& lights) {
  const PackedLights& packed = lights.packed();
  const std::string where = "lights of " + scene.source + ": ";
  if (packed.light_of_triangle.size() != scene.triangles.size())
    throw Error(where + "the light sampler was built for another scene (" +
                std::to_string(packed.light_of_triangle.size()) + " triangles, the scene has " +
                std::to_string(scene.triangles.size()) + ")");
  if (lights.light_count() != scene.lights.size() + packed.emissive.size())
    throw Error(where + "the distribution has " + std::to_string(lights.light_count()) + " entries for " +
                std::to_string(scene.lights.size()) + " punctual lights and " +
                std::to_string(packed.emissive.size()) + " emissive triangles");
  return packed;
}

#ifdef SST_HAVE_VULKAN

GpuLights::GpuLights(const VulkanContext& context, const Scene& scene, const LightSampler& lights)
    : GpuLights(context, pack_lights(scene, lights)) {}

GpuLights::GpuLights(const VulkanContext& context, const PackedLights& packed)
    : header_(packed.header),
      header_buffer_(upload_buffer(context, std::span<const glsl::LightHeader>(&packed.header, 1), "lights: header")),
      punctual_(upload_buffer(context, packed.punctual, "lights: punctual lights")),
      distribution_(upload_buffer(context, packed.distribution, "lights: distribution")),
      emissive_(upload_buffer(context, packed.emissive, "lights: emissive triangles")),
      light_of_triangle_(upload_buffer(context, packed.light_of_triangle, "lights: light of triangle")),
      tree_(upload_buffer(context, std::span<const glsl::EmitterNode>(packed.tree), "lights: emitter tree")) {}

std::vector<const GpuBuffer*> GpuLights::buffers() const {
  return {header_buffer_.get(), punctual_.get(), distribution_.get(), emissive_.get(), light_of_triangle_.get(),
          tree_.get()};
}

size_t GpuLights::bytes() const {
  return header_buffer_->size() + punctual_->size() + distribution_->size() + emissive_->size() +
         light_of_triangle_->size() + tree_->size();
}

std::vector<uint32_t> GpuLights::sampler_specialization() const {
  std::vector<uint32_t> values(SST_SPEC_COUNT, SST_SPEC_UNSET);
  values[SST_SPEC_LIGHT_SAMPLER] = header_.sampler_kind;
  return values;
}
#endif  // SST_HAVE_VULKAN

}  // namespace sst::gpu
