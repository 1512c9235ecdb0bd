// What every method on the Vulkan backend renders with: the device, and the scene, its BVH and its
// lights uploaded to it. Built once per render by render_frame (core/pipeline/renderer.cpp) and
// handed to the method's Vulkan side (gpu/vulkan_method.h).
#pragma once
#include <memory>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"
#include "gpu/acceleration_structure.h"
#include "gpu/bvh_upload.h"
#include "gpu/compute_pipeline.h"
#include "gpu/light_upload.h"
#include "gpu/scene_upload.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

class GpuRenderContext {
 public:
  // Throws sst::Error (one line) when the device cannot be opened or the scene does not fit it.
  // `bvh` is the scene's flat BVH (build_flat_bvh), as the CPU side of the render traces it.
  // `accel`: how the shaders trace rays: "flat" (that BVH, traversed in the shaders), "rayquery"
  // (the device's ray queries over acceleration structures; an error where it has none) or
  // "auto" (rayquery on a GPU that has them, flat elsewhere, lavapipe included, whose images then
  // equal the CPU's bit for bit).
  GpuRenderContext(int device, const Scene& scene, const LightSampler& lights, const FlatBvh& bvh,
                   const std::string& accel = "flat");
  GpuRenderContext(const GpuRenderContext&) = delete;
  GpuRenderContext& operator=(const GpuRenderContext&) = delete;

  const VulkanContext& vulkan() const { return vulkan_; }
  const GpuScene& scene() const { return *scene_; }
  const GpuBvh& bvh() const { return *bvh_; }
  const GpuLights& lights() const { return *lights_; }
  // "flat" or "rayquery": what the shaders trace.
  const std::string& accel() const { return accel_; }
  // The scene's top-level acceleration structure (rayquery), else VK_NULL_HANDLE.
  VkAccelerationStructureKHR top_level() const { return structure_ ? structure_->top_level() : VK_NULL_HANDLE; }
  // A rendering shader's pipeline (ComputePipeline's arguments): its ray-query build (<shader>_rq)
  // bound to the acceleration structure when the render traces with ray queries.
  std::unique_ptr<ComputePipeline> make_pipeline(const std::string& shader, uint32_t buffer_count,
                                                 uint32_t push_constant_bytes,
                                                 std::vector<uint32_t> specialization = {}) const;
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
  std::unique_ptr<GpuAccelerationStructure> structure_;
  std::string accel_ = "flat";
  float ray_epsilon_ = 0.0f;
  size_t bvh_nodes_ = 0;
  double bvh_build_ms_ = 0.0, upload_ms_ = 0.0;
};

}  // namespace sst::gpu
