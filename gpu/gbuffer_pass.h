// The first-hit (G-buffer) stage on the GPU: camera rays through the flat BVH, surfaces
// evaluated as on the CPU, averaged per pixel into the AOVs of FrameOutput (albedo, normal, depth)
// and the emission the camera sees. The methods trace their own camera rays inside their passes
// (pt.comp, many_light.comp) with the same code; this pass checks that code against the CPU's AOVs.
#pragma once
#include <memory>

#include "core/image/image.h"
#include "core/render/camera.h"
#include "gpu/bvh_upload.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/scene_upload.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

struct GBufferImages {
  Image albedo, normal, emission;  // RGB
  Image depth;                     // 1 channel
  double gpu_ms = 0.0;             // the dispatch, from timestamps
};

// Renders `spp` samples per pixel (sample indices 0..spp-1 of pixel_sampler(seed, pixel, i)).
GBufferImages render_gbuffer(const VulkanContext& context, const GpuScene& scene, const GpuBvh& bvh,
                             const PinholeCamera& camera, int width, int height, uint32_t seed, int spp);

}  // namespace sst::gpu
