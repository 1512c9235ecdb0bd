// What every method on the Vulkan backend renders with: the device, and the scene, its BVH and its
// lights uploaded to it. Built once per render by render_frame (core/pipeline/renderer.cpp) and
// handed to the method's Vulkan side (gpu/vulkan_method.h).
#pragma once
#include <memory>
#include <nlohmann/json.hpp>

#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"
#include "gpu/bvh_upload.h"
#include "gpu/light_upload.h"
#include "gpu/scene_upload.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

class GpuRenderContext {
 public:
  // Throws sst::Error (one line) when the device cannot be opened or the scene does not fit it.
  // `bvh` is the scene's flat BVH (build_flat_bvh), as the CPU side of the render traces it.
  GpuRenderContext(int device, const Scene& scene, const LightSampler& lights, const FlatBvh& bvh);
  GpuRenderContext(const GpuRenderContext&) = delete;
  GpuRenderContext& operator=(const GpuRenderContext&) = delete;

  const VulkanContext& vulkan() const { return vulkan_; }
  const GpuScene& scene() const { return *scene_; }
  const GpuBvh& bvh() const { return *bvh_; }
  const GpuLights& lights() const { return *lights_; }
  // EmbreeAccel's scene-relative ray offset (scene_ray_epsilon), for core/accel/ray_offset.h.
  float ray_epsilon() const { return ray_epsilon_; }
  // Bindings 0 .. of every rendering shader: the scene (SCENE_BUFFERS(0)), the BVH nodes and
  // triangles (5, 6), the lights (LIGHT_BUFFERS(7)).
  std::vector<const GpuBuffer*> scene_buffers() const;
  static constexpr uint32_t kSceneBufferCount = GpuScene::kBufferCount + 2 + GpuLights::kBufferCount;

  // For the JSON record: the device, where the BVH was built, sizes and setup times.
  nlohmann::json describe() const;

 private:
  VulkanContext vulkan_;
  std::unique_ptr<GpuScene> scene_;
  std::unique_ptr<GpuBvh> bvh_;
  std::unique_ptr<GpuLights> lights_;
  float ray_epsilon_ = 0.0f;
  size_t bvh_nodes_ = 0;
  double bvh_build_ms_ = 0.0, upload_ms_ = 0.0;
};

}  // namespace sst::gpu
