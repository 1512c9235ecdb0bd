// The flat BVH on the GPU: core/accel/flat_bvh.h's node and triangle arrays uploaded as they are
// (their std430 layout is core/accel/bvh_layout.h), which core/accel/bvh_traverse.h traverses.
// The twin of gpu/scene_upload.h and gpu/light_upload.h for the BVH.
#pragma once
#include <vector>

#include "core/accel/flat_bvh.h"
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

// The flat BVH (core/accel/flat_bvh.h) in two storage buffers: nodes, then triangles.
class GpuBvh {
 public:
  GpuBvh(const VulkanContext& context, const FlatBvh& bvh);
  std::vector<const GpuBuffer*> buffers() const { return {&nodes_, &triangles_}; }
  size_t bytes() const { return nodes_.size() + triangles_.size(); }

 private:
  GpuBuffer nodes_, triangles_;
};

}  // namespace sst::gpu
