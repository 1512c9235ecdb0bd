// The first-hit (G-buffer) stage on the GPU (issue 5): camera rays through the flat BVH, surfaces
// evaluated as on the CPU, averaged per pixel into the AOVs of FrameOutput (albedo, normal, depth)
// and the emission the camera sees. The first stage of every method on the Vulkan backend.
#pragma once
#include <memory>

#include "core/accel/flat_bvh.h"
#include "core/image/image.h"
#include "core/render/camera.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/scene_upload.h"
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

struct GBufferImages {
  Image albedo, normal, emission;  // RGB
  Image depth;                     // 1 channel
  double gpu_ms = 0.0;             // the dispatch, from timestamps
};

// Renders `spp` samples per pixel (sample indices 0..spp-1 of PixelSampler(seed, pixel, i)).
GBufferImages render_gbuffer(const VulkanContext& context, const GpuScene& scene, const GpuBvh& bvh,
                             const PinholeCamera& camera, int width, int height, uint32_t seed, int spp);

}  // namespace sst::gpu
