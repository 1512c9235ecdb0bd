// sst_gpu is built without sst_core's compile definitions; keep glm's types declared as they are
// everywhere else in the tool.
#ifndef GLM_FORCE_XYZW_ONLY
#define GLM_FORCE_XYZW_ONLY 1
#endif
#include "gpu/light_upload.h"

#include "core/util/error.h"

namespace sst::gpu {
namespace {

uint32_t light_type_code(LightType type) {
  switch (type) {
    case LightType::Spot: return LIGHT_SPOT;
    case LightType::Directional: return LIGHT_DIRECTIONAL;
    case LightType::Point:
    default: return LIGHT_POINT;
  }
}

// A double cdf value as hi + lo floats: comparing (hi, lo) with a float u gives the double's answer.
glsl::LightCdfEntry cdf_entry(double cdf, float pmf) {
  glsl::LightCdfEntry e{};
  e.cdf_hi = float(cdf);
  e.cdf_lo = float(cdf - double(e.cdf_hi));
  e.pmf = pmf;
  e.reserved = 0u;
  return e;
}

}  // namespace

size_t PackedLights::bytes() const {
  return sizeof header + punctual.size() * sizeof(glsl::LightPunctual) +
         distribution.size() * sizeof(glsl::LightCdfEntry) + emissive.size() * sizeof(glsl::LightEmissive) +
         light_of_triangle.size() * sizeof(uint32_t);
}

PackedLights pack_lights(const Scene& scene, const LightSampler& lights) {
  const DiscreteDistribution& dist = lights.distribution();
  const std::string where = "lights of " + scene.source + ": ";
  if (lights.light_of_triangle().size() != scene.triangles.size())
    throw Error(where + "the light sampler was built for another scene (" +
                std::to_string(lights.light_of_triangle().size()) + " triangles, the scene has " +
                std::to_string(scene.triangles.size()) + ")");
  if (dist.size() != scene.lights.size() + lights.emissive_triangle_count())
    throw Error(where + "the distribution has " + std::to_string(dist.size()) + " entries for " +
                std::to_string(scene.lights.size()) + " punctual lights and " +
                std::to_string(lights.emissive_triangle_count()) + " emissive triangles");

  PackedLights out;
  out.header.punctual_count = uint32_t(scene.lights.size());
  out.header.emissive_count = uint32_t(lights.emissive_triangle_count());
  // An empty distribution picks nothing: the GPU tests distribution_size == 0 as LightSampler
  // tests empty().
  out.header.distribution_size = dist.empty() ? 0u : uint32_t(dist.size());
  out.header.triangle_count = uint32_t(scene.triangles.size());
  out.header.bounds_center = scene.bounds.center();
  out.header.bounds_radius = 0.5f * scene.bounds.diagonal();

  out.punctual.reserve(scene.lights.size());
  for (const PunctualLight& l : scene.lights) {
    glsl::LightPunctual p{};
    p.position = l.position;
    p.type = light_type_code(l.type);
    p.direction = l.direction;
    p.cos_inner = l.cos_inner;
    p.intensity = l.intensity;
    p.cos_outer = l.cos_outer;
    out.punctual.push_back(p);
  }
  if (!dist.empty()) {
    out.distribution.reserve(dist.size());
    for (size_t i = 0; i < dist.size(); ++i) out.distribution.push_back(cdf_entry(dist.cdf()[i], dist.pmfs()[i]));
  }
  const std::vector<uint32_t>& tris = lights.emissive_triangles();
  const std::vector<float>& areas = lights.emissive_triangle_areas();
  out.emissive.reserve(tris.size());
  for (size_t k = 0; k < tris.size(); ++k) out.emissive.push_back({tris[k], areas[k]});
  out.light_of_triangle = lights.light_of_triangle();
  static_assert(LIGHT_NONE == UINT32_MAX);
  return out;
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
      light_of_triangle_(upload_buffer(context, packed.light_of_triangle, "lights: light of triangle")) {}

std::vector<const GpuBuffer*> GpuLights::buffers() const {
  return {header_buffer_.get(), punctual_.get(), distribution_.get(), emissive_.get(), light_of_triangle_.get()};
}

size_t GpuLights::bytes() const {
  return header_buffer_->size() + punctual_->size() + distribution_->size() + emissive_->size() +
         light_of_triangle_->size();
}
#endif  // SST_HAVE_VULKAN

}  // namespace sst::gpu
