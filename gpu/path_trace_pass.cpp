#include "gpu/path_trace_pass.h"

#include <vector>

#include "core/util/error.h"
#include "gpu/compute_pipeline.h"
#include "core/render/camera.h"
#include "gpu/gpu_render_context.h"
#include "gpu/sample_chunks.h"
#include "core/pt/path_trace_layout.h"

namespace sst::gpu {
namespace {

// The pixel's averages exactly as PathTracer::render writes them from its sums.
void write_pixel(const glsl::PathTraceTexel& t, float inv_spp, int x, int y, FrameOutput& frame) {
  frame.direct.set_rgb(x, y, t.direct * inv_spp);
  frame.indirect.set_rgb(x, y, t.indirect * inv_spp);
  frame.color.set_rgb(x, y, (t.direct + t.indirect) * inv_spp);
  frame.albedo.set_rgb(x, y, t.albedo * inv_spp);
  vec3 n = t.normal;
  frame.normal.set_rgb(x, y, glm::length(n) > 0.0f ? glm::normalize(n) : n);
  frame.depth.at(x, y, 0) = t.depth * inv_spp;
  frame.counters.primary_rays += t.primary_rays;
  frame.counters.shadow_rays += t.shadow_rays;
  frame.counters.bounce_rays += t.bounce_rays;
  frame.counters.samples += t.samples;
  frame.counters.nonfinite_samples += t.nonfinite_samples;
}

}  // namespace

GpuPathTraceResult render_path_tracer(const VulkanContext& context, const GpuScene& scene, const GpuBvh& bvh,
                                      const GpuLights& lights, float ray_epsilon, const PinholeCamera& camera,
                                      int width, int height, uint32_t seed, int spp, const PathTracerParams& params,
                                      bool diffuse_only, ComputePipeline* pipeline) {
  if (width <= 0 || height <= 0) throw Error("pt on the GPU: image of " + std::to_string(width) + " x " +
                                             std::to_string(height) + " pixels");
  if (spp <= 0) throw Error("pt on the GPU: spp must be >= 1 (got " + std::to_string(spp) + ")");
  const size_t pixels = size_t(width) * size_t(height);
  std::unique_ptr<GpuBuffer> texel_buffer = make_buffer(
      context, pixels, sizeof(glsl::PathTraceTexel),
      "pt: per-pixel sums of a " + std::to_string(width) + "x" + std::to_string(height) + " image, pixels");
  GpuBuffer& texels = *texel_buffer;
  std::vector<const GpuBuffer*> buffers = scene.buffers();
  for (const GpuBuffer* b : bvh.buffers()) buffers.push_back(b);
  for (const GpuBuffer* b : lights.buffers()) buffers.push_back(b);
  buffers.push_back(&texels);

  glsl::PathTraceParams push{};
  push.view = view_params(camera, width, height, seed);
  push.ray_epsilon = ray_epsilon;
  push.max_bounces = params.max_bounces;
  push.rr_min_bounces = params.rr_min_bounces;
  push.diffuse_only = diffuse_only ? 1u : 0u;

  std::unique_ptr<ComputePipeline> own;
  if (!pipeline) pipeline = (own = make_path_trace_pipeline(context)).get();
  GpuPathTraceResult out;
  const uint32_t groups_x = (uint32_t(width) + 7) / 8, groups_y = (uint32_t(height) + 7) / 8;
  for (SampleChunks chunks(spp, context.info().type == "cpu"); !chunks.done();) {
    push.view.sample_offset = uint32_t(chunks.offset());
    push.view.spp = uint32_t(chunks.size());
    double ms = pipeline->dispatch(buffers, &push, groups_x, groups_y);
    out.gpu_ms += ms;
    ++out.dispatches;
    chunks.advance(ms);
  }

  std::vector<glsl::PathTraceTexel> sums(pixels);
  texels.download(std::span<glsl::PathTraceTexel>(sums));
  out.frame.allocate(width, height);
  const float inv_spp = 1.0f / float(spp);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) write_pixel(sums[size_t(y) * size_t(width) + size_t(x)], inv_spp, x, y, out.frame);
  return out;
}

std::unique_ptr<ComputePipeline> make_path_trace_pipeline(const VulkanContext& context) {
  return std::make_unique<ComputePipeline>(context, "pt", GpuRenderContext::kSceneBufferCount + 1,
                                           uint32_t(sizeof(glsl::PathTraceParams)));
}

GpuPathTraceResult render_path_tracer(const GpuRenderContext& gpu, ComputePipeline& pipeline, const PinholeCamera& camera,
                                      int width, int height, uint32_t seed, int spp, const PathTracerParams& params,
                                      bool diffuse_only) {
  return render_path_tracer(gpu.vulkan(), gpu.scene(), gpu.bvh(), gpu.lights(), gpu.ray_epsilon(), camera, width,
                            height, seed, spp, params, diffuse_only, &pipeline);
}

}  // namespace sst::gpu
