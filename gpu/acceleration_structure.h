// The scene as Vulkan acceleration structures, for hardware ray queries (--accel rayquery): one
// bottom-level structure over every scene triangle, in scene order (a ray query's primitive index is
// the scene triangle index, as the flat BVH's hit reports it), and a top-level structure with that
// one instance at the identity. The triangles are one geometry: opaque when no material is
// alpha-tested, else non-opaque, so that each candidate hit runs the alpha test the flat BVH runs
// (gpu/shaders/ray_queries.glsl). Ray queries cull no face, as the flat BVH does not.
//
// Built on the device when the render context is made (GpuRenderContext), which happens again for
// every frame of a sequence, so animated geometry gets a fresh build rather than a refit.
#pragma once
#include <vulkan/vulkan.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "core/scene/scene.h"
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

class GpuAccelerationStructure {
 public:
  // Throws sst::Error (one line) when the device has no ray queries (DeviceInfo::ray_query) or a
  // build fails.
  GpuAccelerationStructure(const VulkanContext& context, const Scene& scene);
  ~GpuAccelerationStructure();
  GpuAccelerationStructure(const GpuAccelerationStructure&) = delete;
  GpuAccelerationStructure& operator=(const GpuAccelerationStructure&) = delete;

  VkAccelerationStructureKHR top_level() const { return top_; }

  // For the record: the sizes of the structures and of the build's inputs and scratch memory
  // (bytes), the host's wall time of the whole build and the device's timestamps around it (ms).
  nlohmann::json describe() const;

 private:
  const VulkanContext& context_;
  std::unique_ptr<GpuBuffer> positions_, indices_, instances_, bottom_buffer_, top_buffer_;
  VkAccelerationStructureKHR bottom_ = VK_NULL_HANDLE, top_ = VK_NULL_HANDLE;
  size_t scratch_bytes_ = 0;
  uint32_t triangles_ = 0;
  bool opaque_ = true;
  double build_ms_ = 0.0, build_gpu_ms_ = 0.0;
};

}  // namespace sst::gpu
