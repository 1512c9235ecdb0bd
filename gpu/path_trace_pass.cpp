#include "gpu/path_trace_pass.h"

#include <algorithm>
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
  PathSample sum;
  sum.direct = t.direct;
  sum.indirect = t.indirect;
  sum.albedo = t.albedo;
  sum.normal = t.normal;
  sum.depth = t.depth;
  write_path_means(sum, inv_spp, x, y, frame);
  frame.counters.primary_rays += t.primary_rays;
  frame.counters.shadow_rays += t.shadow_rays;
  frame.counters.bounce_rays += t.bounce_rays;
  frame.counters.samples += t.samples;
  frame.counters.nonfinite_samples += t.nonfinite_samples;
}

// The frame from the per-pixel sums of `spp` samples.
void write_frame(const GpuBuffer& texels, int width, int height, int spp, FrameOutput& frame) {
  std::vector<glsl::PathTraceTexel> sums(size_t(width) * size_t(height));
  texels.download(std::span<glsl::PathTraceTexel>(sums));
  frame.allocate(width, height);
  const float inv_spp = 1.0f / float(spp);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) write_pixel(sums[size_t(y) * size_t(width) + size_t(x)], inv_spp, x, y, frame);
}

void check_size(int width, int height, int spp) {
  if (width <= 0 || height <= 0) throw Error("pt on the GPU: image of " + std::to_string(width) + " x " +
                                             std::to_string(height) + " pixels");
  if (spp <= 0) throw Error("pt on the GPU: spp must be >= 1 (got " + std::to_string(spp) + ")");
}

glsl::PathTraceParams push_params(const PinholeCamera& camera, int width, int height, uint32_t seed, float ray_epsilon,
                                  const PathTracerParams& params, uint32_t path_flags) {
  glsl::PathTraceParams push{};
  push.view = view_params(camera, width, height, seed);
  push.ray_epsilon = ray_epsilon;
  push.max_bounces = params.max_bounces;
  push.rr_min_bounces = params.rr_min_bounces;
  push.path_flags = path_flags;
  return push;
}

}  // namespace

GpuPathTraceResult render_path_tracer(const VulkanContext& context, const GpuScene& scene, const GpuBvh& bvh,
                                      const GpuLights& lights, float ray_epsilon, const PinholeCamera& camera,
                                      int width, int height, uint32_t seed, int spp, const PathTracerParams& params,
                                      uint32_t path_flags, ComputePipeline* pipeline) {
  check_size(width, height, spp);
  const size_t pixels = size_t(width) * size_t(height);
  std::unique_ptr<GpuBuffer> texel_buffer = make_buffer(
      context, pixels, sizeof(glsl::PathTraceTexel),
      "pt: per-pixel sums of a " + std::to_string(width) + "x" + std::to_string(height) + " image, pixels");
  GpuBuffer& texels = *texel_buffer;
  std::vector<const GpuBuffer*> buffers = scene.buffers();
  for (const GpuBuffer* b : bvh.buffers()) buffers.push_back(b);
  for (const GpuBuffer* b : lights.buffers()) buffers.push_back(b);
  buffers.push_back(&texels);

  glsl::PathTraceParams push = push_params(camera, width, height, seed, ray_epsilon, params, path_flags);

  std::unique_ptr<ComputePipeline> own;
  if (!pipeline) pipeline = (own = make_path_trace_pipeline(context, lights)).get();
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

  write_frame(texels, width, height, spp, out.frame);
  return out;
}

std::unique_ptr<ComputePipeline> make_path_trace_pipeline(const VulkanContext& context, const GpuLights& lights,
                                                          VkAccelerationStructureKHR top_level) {
  return std::make_unique<ComputePipeline>(context, "pt", GpuRenderContext::kSceneBufferCount + 1,
                                           uint32_t(sizeof(glsl::PathTraceParams)), lights.sampler_specialization(),
                                           top_level);
}

GpuPathTraceResult render_path_tracer(const GpuRenderContext& gpu, ComputePipeline& pipeline, const PinholeCamera& camera,
                                      int width, int height, uint32_t seed, int spp, const PathTracerParams& params,
                                      uint32_t path_flags) {
  return render_path_tracer(gpu.vulkan(), gpu.scene(), gpu.bvh(), gpu.lights(), gpu.ray_epsilon(), camera, width,
                            height, seed, spp, params, path_flags, &pipeline);
}

std::unique_ptr<PathWavefrontPipelines> make_path_wavefront_pipelines(const GpuRenderContext& gpu) {
  auto out = std::make_unique<PathWavefrontPipelines>();
  for (int stage = 0; stage < 5; ++stage)
    out->stages[stage] =
        gpu.make_pipeline("pt_wavefront_" + std::to_string(stage), GpuRenderContext::kSceneBufferCount + 3,
                          uint32_t(sizeof(glsl::PathWaveParams)), gpu.lights().sampler_specialization());
  return out;
}

GpuPathTraceResult render_path_tracer_wavefront(const GpuRenderContext& gpu, PathWavefrontPipelines& pipelines,
                                               const PinholeCamera& camera, int width, int height, uint32_t seed,
                                               int spp, const PathTracerParams& params, uint32_t path_flags) {
  check_size(width, height, spp);
  const VulkanContext& context = gpu.vulkan();
  const size_t pixels = size_t(width) * size_t(height);
  const size_t slots = std::min(pixels, kPathWavePaths);
  std::unique_ptr<GpuBuffer> texels = make_buffer(
      context, pixels, sizeof(glsl::PathTraceTexel),
      "pt: per-pixel sums of a " + std::to_string(width) + "x" + std::to_string(height) + " image, pixels");
  std::unique_ptr<GpuBuffer> states = make_buffer(context, slots, glsl::kPathWaveStateBytes, "pt wavefront: path states");
  std::unique_ptr<GpuBuffer> status = make_buffer(context, 1, sizeof(glsl::PathWaveStatus), "pt wavefront: status");
  std::vector<const GpuBuffer*> buffers = gpu.scene().buffers();
  for (const GpuBuffer* b : gpu.bvh().buffers()) buffers.push_back(b);
  for (const GpuBuffer* b : gpu.lights().buffers()) buffers.push_back(b);
  buffers.push_back(texels.get());
  buffers.push_back(states.get());
  buffers.push_back(status.get());

  glsl::PathWaveParams push{};
  push.pt = push_params(camera, width, height, seed, gpu.ray_epsilon(), params, path_flags);
  push.pt.view.spp = 1u;
  GpuPathTraceResult out;
  const char* names[5] = {"camera", "shade", "shadow", "bounce", "accumulate"};
  double stage_ms[5] = {0, 0, 0, 0, 0};
  auto run = [&](int stage, uint32_t paths) {
    stage_ms[stage] += pipelines.stages[stage]->dispatch(buffers, &push, uint32_t((paths + 63) / 64));
    ++out.dispatches;
  };
  const glsl::PathWaveStatus zero{0u, 0u};
  // Each pixel's samples in order, as the megakernel adds them.
  for (int sample = 0; sample < spp; ++sample) {
    push.pt.view.sample_offset = uint32_t(sample);
    for (size_t first = 0; first < pixels; first += slots) {
      push.first_pixel = uint32_t(first);
      push.path_count = uint32_t(std::min(slots, pixels - first));
      run(0, push.path_count);
      // Vertex k's shade, shadow and bounce; the bounce stage counts the paths left to shade.
      for (int k = 1; k <= params.max_bounces + 1; ++k) {
        run(1, push.path_count);
        run(2, push.path_count);
        status->upload(std::span<const glsl::PathWaveStatus>(&zero, 1));
        run(3, push.path_count);
        glsl::PathWaveStatus st{0u, 0u};
        status->download(std::span<glsl::PathWaveStatus>(&st, 1));
        if (st.overflow)
          throw Error("pt wavefront: a path state is larger than the " + std::to_string(glsl::kPathWaveStateBytes) +
                      " bytes allocated for it (kPathWaveStateBytes, core/pt/path_trace_layout.h)");
        if (st.live == 0u) break;
      }
      run(4, push.path_count);
    }
  }
  for (int stage = 0; stage < 5; ++stage) {
    out.stage_ms.emplace_back(names[stage], stage_ms[stage]);
    out.gpu_ms += stage_ms[stage];
  }
  write_frame(*texels, width, height, spp, out.frame);
  return out;
}

}  // namespace sst::gpu
