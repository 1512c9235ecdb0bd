#include "gpu/bvh_upload.h"

namespace sst::gpu {

GpuBvh::GpuBvh(const VulkanContext& context, const FlatBvh& bvh)
    : nodes_(context, bvh.nodes.size() * sizeof(glsl::BvhNode)),
      triangles_(context, bvh.triangles.size() * sizeof(glsl::BvhTriangle)) {
  nodes_.upload(std::span<const glsl::BvhNode>(bvh.nodes));
  triangles_.upload(std::span<const glsl::BvhTriangle>(bvh.triangles));
}

}  // namespace sst::gpu
