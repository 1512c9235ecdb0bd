// The sampling stage of the VPL methods on the GPU (gpu/shaders/many_light.comp): camera rays,
// direct light and one indirect estimate per pixel sample, accumulated into the images and
// counters that core/manylight/many_light_method.cpp produces on the CPU, computed from the sums
// with the same expressions.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/image/image.h"
#include "core/render/camera.h"
#include "core/render/frame.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_render_context.h"
#include "gpu/many_light_upload.h"

namespace sst::gpu {

struct ManyLightPassOutput {
  Image variance;         // of each pixel's indirect mean (indirect_variance)
  Image traversal_depth;  // tree nodes visited per indirect sample, 1 channel
  std::vector<uint64_t> depth_histogram = std::vector<uint64_t>(65, 0);
  uint64_t indirect_samples = 0, nodes_visited = 0;
  uint64_t loop_budget_hits = 0;  // samples near lavapipe's loop limit (bvh_traverse.h); an error there
  double gpu_ms = 0.0;       // all dispatches, from timestamps
  int dispatches = 0;
};

// The sampling shader, compiled by the driver (a stage of its own) for the sampler `params` and
// gpu's light sampler: only that method's estimate is compiled (gpu/shaders/specialization.glsl).
std::unique_ptr<ComputePipeline> make_many_light_pipeline(const GpuRenderContext& gpu, const SamplerParams& params);

// Renders `spp` samples per pixel into `frame` (color, direct, indirect, albedo, normal, depth
// and counters), which must be allocated at width x height. compensation_max_bounces and
// compensation_rr_min_bounces: many_light_direct_config's (core/manylight/direct_pass.h).
ManyLightPassOutput render_many_light(const GpuRenderContext& gpu, ComputePipeline& pipeline,
                                      const GpuManyLightInputs& inputs, const PinholeCamera& camera, uint32_t seed,
                                      int spp, uint32_t path_flags, int compensation_max_bounces,
                                      int compensation_rr_min_bounces, FrameOutput& frame);

}  // namespace sst::gpu
