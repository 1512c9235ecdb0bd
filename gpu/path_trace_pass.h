// The `pt` method on the Vulkan backend: the twin of PathTracer::render
// (core/pt/path_tracer.cpp). gpu/shaders/pt.comp traces every pixel's paths with the CPU's
// random numbers through the flat BVH; this pass dispatches it in chunks of samples and turns the
// per-pixel sums into the FrameOutput the CPU fills (color, direct, indirect, albedo, normal,
// depth and the ray counters).
#pragma once
#include "core/render/camera.h"
#include "core/render/frame.h"
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/pt/path_tracer.h"
#include "gpu/compute_pipeline.h"
#include "gpu/bvh_upload.h"
#include "gpu/light_upload.h"
#include "gpu/scene_upload.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

class GpuRenderContext;

struct GpuPathTraceResult {
  FrameOutput frame;
  double gpu_ms = 0.0;  // all dispatches, from timestamps
  int dispatches = 0;
  // The wavefront's GPU time per stage (camera, shade, shadow, bounce, accumulate); empty for the
  // megakernel.
  std::vector<std::pair<std::string, double>> stage_ms;
};

// Renders `spp` camera paths per pixel (sample indices 0..spp-1 of pixel_sampler(seed, pixel, i)),
// as PathTracer::render does with the same seed, params and options (`path_flags`: render_flags of
// the options, core/render/render_options.h). `ray_epsilon` is
// scene_ray_epsilon(scene) (core/accel/embree_accel.h). Samples are dispatched in chunks (the
// first of one sample per pixel, the rest sized from its time; gpu/sample_chunks.h), so no single
// dispatch runs long. Bindings of pt.comp: 0..4 scene, 5..6 BVH, 7..12 lights, 13 the texels.
GpuPathTraceResult render_path_tracer(const VulkanContext& context, const GpuScene& scene, const GpuBvh& bvh,
                                      const GpuLights& lights, float ray_epsilon, const PinholeCamera& camera,
                                      int width, int height, uint32_t seed, int spp, const PathTracerParams& params,
                                      uint32_t path_flags, ComputePipeline* pipeline = nullptr);

// pt.comp compiled by the driver for `lights`' sampler, tracing the flat BVH or, given the scene's
// acceleration structure, ray queries (sst-render times it as its own stage).
std::unique_ptr<ComputePipeline> make_path_trace_pipeline(const VulkanContext& context, const GpuLights& lights,
                                                          VkAccelerationStructureKHR top_level = VK_NULL_HANDLE);

// The same with everything uploaded once per render (gpu/gpu_render_context.h) and the pipeline made.
GpuPathTraceResult render_path_tracer(const GpuRenderContext& gpu, ComputePipeline& pipeline, const PinholeCamera& camera,
                                      int width, int height, uint32_t seed, int spp, const PathTracerParams& params,
                                      uint32_t path_flags);

// The wavefront (gpu/shaders/pt_wavefront.comp): the same image bits as the megakernel, each stage
// of the paths a dispatch of its own over waves of at most kPathWavePaths paths (one sample of a
// range of pixels each), the states kept in a buffer between stages.
constexpr size_t kPathWavePaths = size_t(1) << 16;
struct PathWavefrontPipelines {
  std::unique_ptr<ComputePipeline> stages[5];  // pt_wavefront_0 .. _4
};
std::unique_ptr<PathWavefrontPipelines> make_path_wavefront_pipelines(const GpuRenderContext& gpu);
GpuPathTraceResult render_path_tracer_wavefront(const GpuRenderContext& gpu, PathWavefrontPipelines& pipelines,
                                               const PinholeCamera& camera, int width, int height, uint32_t seed,
                                               int spp, const PathTracerParams& params, uint32_t path_flags);

}  // namespace sst::gpu
