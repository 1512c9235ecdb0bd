#include "gpu/many_light_pass.h"

#include "gpu/compute_pipeline.h"
#include "gpu/frame_params.h"
#include "gpu/sample_chunks.h"
#include "core/render/frame_layout.h"

namespace sst::gpu {
namespace {

struct ManyLightPush {
  glsl::FrameParams frame;
  float ray_epsilon;
  uint32_t diffuse_only;
};
static_assert(sizeof(ManyLightPush) == 88);

// ManyLightMethod::render's per-pixel epilogue, from the sums.
void write_pixel(const glsl::ManyLightTexel& t, int x, int y, int spp, FrameOutput& frame, ManyLightPassOutput& out) {
  float inv = 1.0f / float(spp);
  vec3 mean = t.indirect * inv;
  frame.direct.set_rgb(x, y, t.direct * inv);
  frame.indirect.set_rgb(x, y, mean);
  frame.color.set_rgb(x, y, (t.direct + t.indirect) * inv);
  frame.albedo.set_rgb(x, y, t.albedo * inv);
  frame.normal.set_rgb(x, y, glm::length(t.normal) > 0.0f ? glm::normalize(t.normal) : t.normal);
  frame.depth.at(x, y, 0) = t.depth * inv;
  vec3 var = spp > 1 ? glm::max(t.indirect2 * inv - mean * mean, vec3(0.0f)) / float(spp - 1) : vec3(0.0f);
  out.variance.set_rgb(x, y, var);
  out.traversal_depth.at(x, y, 0) = t.indirect_samples ? float(t.nodes) / float(t.indirect_samples) : 0.0f;
  frame.counters.primary_rays += t.primary_rays;
  frame.counters.shadow_rays += t.shadow_rays;
  frame.counters.bounce_rays += t.bounce_rays;
  frame.counters.samples += t.samples;
  frame.counters.nonfinite_samples += t.nonfinite;
  out.loop_budget_hits += t.loop_budget_hits;
  out.indirect_samples += t.indirect_samples;
  out.nodes_visited += t.nodes;
}

}  // namespace

constexpr uint32_t kBufferCount = GpuRenderContext::kSceneBufferCount + kManyLightBufferCount + 2;

std::unique_ptr<ComputePipeline> make_many_light_pipeline(const GpuRenderContext& gpu) {
  return std::make_unique<ComputePipeline>(gpu.vulkan(), "many_light", kBufferCount, uint32_t(sizeof(ManyLightPush)));
}

ManyLightPassOutput render_many_light(const GpuRenderContext& gpu, ComputePipeline& pipeline,
                                      const GpuManyLightInputs& inputs, const PinholeCamera& camera, uint32_t seed,
                                      int spp, bool diffuse_only, FrameOutput& frame) {
  const int width = frame.color.width, height = frame.color.height;
  const size_t pixels = size_t(width) * size_t(height);
  const VulkanContext& vk = gpu.vulkan();
  std::unique_ptr<GpuBuffer> texel_buffer =
      make_buffer(vk, pixels, sizeof(glsl::ManyLightTexel), "sampling: per-pixel sums of a " +
                                                               std::to_string(width) + "x" + std::to_string(height) +
                                                               " image, pixels");
  GpuBuffer& texels = *texel_buffer;
  GpuBuffer histogram(vk, 65 * sizeof(uint32_t));
  std::vector<uint32_t> zeros(65, 0);
  histogram.upload(std::span<const uint32_t>(zeros));

  std::vector<const GpuBuffer*> buffers = gpu.scene_buffers();
  for (const GpuBuffer* b : inputs.buffers()) buffers.push_back(b);
  buffers.push_back(&texels);
  buffers.push_back(&histogram);

  ManyLightPassOutput out;

  ManyLightPush push{frame_params(camera, width, height, seed), gpu.ray_epsilon(), diffuse_only ? 1u : 0u};
  const uint32_t groups_x = (uint32_t(width) + 7) / 8, groups_y = (uint32_t(height) + 7) / 8;
  const bool lavapipe = vk.info().type == "cpu";
  for (SampleChunks chunks(spp, lavapipe); !chunks.done();) {
    push.frame.sample_offset = uint32_t(chunks.offset());
    push.frame.spp = uint32_t(chunks.size());
    double ms = pipeline.dispatch(buffers, &push, groups_x, groups_y);
    out.gpu_ms += ms;
    ++out.dispatches;
    chunks.advance(ms);
  }

  std::vector<glsl::ManyLightTexel> sums(pixels);
  texels.download(std::span<glsl::ManyLightTexel>(sums));
  std::vector<uint32_t> bins(65);
  histogram.download(std::span<uint32_t>(bins));
  for (size_t i = 0; i < bins.size(); ++i) out.depth_histogram[i] = bins[i];
  out.variance = Image(width, height);
  out.traversal_depth = Image(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) write_pixel(sums[size_t(y) * size_t(width) + size_t(x)], x, y, spp, frame, out);
  if (lavapipe && out.loop_budget_hits > 0)
    throw Error(std::to_string(out.loop_budget_hits) +
                " pixel samples needed more shader loop iterations than lavapipe runs (65535 per invocation); "
                "its image would be wrong: use fewer VPLs for 'exhaustive', or a GPU, or --backend cpu");
  return out;
}

}  // namespace sst::gpu
