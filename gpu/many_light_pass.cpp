#include "gpu/many_light_pass.h"

#include <algorithm>
#include <utility>

#include "core/accel/bvh_layout.h"
#include "gpu/compute_pipeline.h"
#include "core/render/camera.h"
#include "gpu/sample_chunks.h"
#include "gpu/shaders/specialization_ids.h"
#include "core/render/frame_layout.h"
#include "core/manylight/many_light_method.h"

namespace sst::gpu {
namespace {

using glsl::ManyLightPush;

// ManyLightMethod::render's per-pixel epilogue, from the sums.
void write_pixel(const glsl::ManyLightTexel& t, int x, int y, int spp, FrameOutput& frame, ManyLightPassOutput& out) {
  ManyLightPixelSums sums;
  sums.path.direct = t.direct;
  sums.path.indirect = t.indirect;
  sums.path.albedo = t.albedo;
  sums.path.normal = t.normal;
  sums.path.depth = t.depth;
  sums.indirect2 = t.indirect2;
  sums.nodes = t.nodes;
  sums.indirect_samples = t.indirect_samples;
  write_many_light_pixel(sums, spp, x, y, frame, out.variance, out.traversal_depth);
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

constexpr uint32_t kBufferCount = GpuRenderContext::kSceneBufferCount + kManyLightBufferCount + 4;

std::unique_ptr<ComputePipeline> make_many_light_pipeline(const GpuRenderContext& gpu, const SamplerParams& params) {
  std::vector<uint32_t> specialization = gpu.lights().sampler_specialization();
  specialization[SST_SPEC_MANY_LIGHT_METHOD] = params.method;
  specialization[SST_SPEC_OWN_DIRECT] = params.rtslc_direct_cut_max_size != 0u ? 1u : 0u;
  return gpu.make_pipeline("many_light", kBufferCount, uint32_t(sizeof(ManyLightPush)), std::move(specialization));
}

ManyLightPassOutput render_many_light(const GpuRenderContext& gpu, ComputePipeline& pipeline,
                                      const GpuManyLightInputs& inputs, const PinholeCamera& camera, uint32_t seed,
                                      int spp, uint32_t path_flags, int compensation_max_bounces,
                                      int compensation_rr_min_bounces, FrameOutput& frame) {
  const int width = frame.color.width, height = frame.color.height;
  const size_t pixels = size_t(width) * size_t(height);
  const VulkanContext& vk = gpu.vulkan();
  std::unique_ptr<GpuBuffer> texel_buffer =
      make_buffer(vk, pixels, sizeof(glsl::ManyLightTexel), "sampling: per-pixel sums of a " +
                                                               std::to_string(width) + "x" + std::to_string(height) +
                                                               " image, pixels");
  GpuBuffer& texels = *texel_buffer;
  GpuBuffer dispatch_words(vk, ML_DISPATCH_WORDS * sizeof(uint32_t));
  std::vector<uint32_t> words(ML_DISPATCH_WORDS, 0);
  dispatch_words.upload(std::span<const uint32_t>(words));

  // An exhaustive sum over many VPLs exceeds lavapipe's loop limit in one invocation: there it
  // is split into slices of VPLs, one dispatch each (ManyLightPush).
  const bool lavapipe = vk.info().type == "cpu";
  const uint32_t vpl_count = inputs.params().vpl_count;
  const bool slice_vpls = lavapipe && inputs.params().method == ML_METHOD_exhaustive && vpl_count > 0;
  const size_t slice_count = slice_vpls ? pixels : 1;
  std::unique_ptr<GpuBuffer> slices_a = make_buffer(vk, slice_count, sizeof(glsl::ManyLightSlice),
                                                    "sampling: running sums of the VPL slices, pixels");
  std::unique_ptr<GpuBuffer> slices_b = make_buffer(vk, slice_count, sizeof(glsl::ManyLightSlice),
                                                    "sampling: running sums of the VPL slices, pixels");

  std::vector<const GpuBuffer*> buffers = gpu.scene_buffers();
  for (const GpuBuffer* b : inputs.buffers()) buffers.push_back(b);
  buffers.push_back(&texels);
  buffers.push_back(&dispatch_words);
  const size_t slices_in = buffers.size();
  buffers.push_back(slices_a.get());
  buffers.push_back(slices_b.get());

  ManyLightPassOutput out;

  ManyLightPush push{view_params(camera, width, height, seed), gpu.ray_epsilon(), path_flags, 0u,
                     0xFFFFFFFFu, ML_SLICE_FIRST | ML_SLICE_LAST, compensation_max_bounces,
                     compensation_rr_min_bounces};
  const uint32_t groups_x = (uint32_t(width) + 7) / 8, groups_y = (uint32_t(height) + 7) / 8;
  if (!slice_vpls) {
    for (SampleChunks chunks(spp, lavapipe); !chunks.done();) {
      push.view.sample_offset = uint32_t(chunks.offset());
      push.view.spp = uint32_t(chunks.size());
      double ms = pipeline.dispatch(buffers, &push, groups_x, groups_y);
      out.gpu_ms += ms;
      ++out.dispatches;
      chunks.advance(ms);
    }
    dispatch_words.download(std::span<uint32_t>(words));
  } else {
    // Each slice is sized from the loop iterations the last one took, to half the budget; a slice
    // that came near the limit anyway is undone (the texels and words saved before it) and
    // retried at half its size.
    uint32_t slice_size = 32;
    std::vector<glsl::ManyLightTexel> saved(pixels);
    push.view.spp = 1;
    for (int sample = 0; sample < spp; ++sample) {
      push.view.sample_offset = uint32_t(sample);
      for (uint32_t first = 0; first < vpl_count;) {
        uint32_t end = first + std::min(slice_size, vpl_count - first);
        push.vpl_first = first;
        push.vpl_end = end;
        push.slice_flags = (first == 0 ? ML_SLICE_FIRST : 0u) | (end == vpl_count ? ML_SLICE_LAST : 0u);
        // The frame's first slice overwrites the texels; every later one adds to them.
        const bool adds_to_texels = sample > 0 || first > 0;
        if (adds_to_texels) texels.download(std::span<glsl::ManyLightTexel>(saved));
        words[ML_DISPATCH_BUDGET_HITS] = 0;
        words[ML_DISPATCH_MAX_ITERATIONS] = 0;
        dispatch_words.upload(std::span<const uint32_t>(words));
        out.gpu_ms += pipeline.dispatch(buffers, &push, groups_x, groups_y);
        ++out.dispatches;
        std::vector<uint32_t> after(ML_DISPATCH_WORDS);
        dispatch_words.download(std::span<uint32_t>(after));
        if (after[ML_DISPATCH_BUDGET_HITS] > 0) {
          if (end - first == 1)
            throw Error("one VPL's shadow rays need more shader loop iterations than lavapipe runs (65535 per "
                        "invocation): use a GPU, or --backend cpu");
          if (adds_to_texels) texels.upload(std::span<const glsl::ManyLightTexel>(saved));
          slice_size = std::max(1u, (end - first) / 2);
          continue;
        }
        words = after;
        uint32_t iterations = std::max(1u, after[ML_DISPATCH_MAX_ITERATIONS]);
        double fit = double(end - first) * (0.5 * BVH_LAVAPIPE_LOOP_BUDGET) / double(iterations);
        slice_size = uint32_t(std::clamp(fit, 1.0, 4.0 * double(end - first)));
        std::swap(buffers[slices_in], buffers[slices_in + 1]);
        first = end;
      }
    }
  }

  std::vector<glsl::ManyLightTexel> sums(pixels);
  texels.download(std::span<glsl::ManyLightTexel>(sums));
  for (size_t i = 0; i < out.depth_histogram.size(); ++i) out.depth_histogram[i] = words[i];
  out.variance = Image(width, height);
  out.traversal_depth = Image(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) write_pixel(sums[size_t(y) * size_t(width) + size_t(x)], x, y, spp, frame, out);
  if (lavapipe && out.loop_budget_hits > 0)
    throw Error(std::to_string(out.loop_budget_hits) +
                " pixel samples needed more shader loop iterations than lavapipe runs (65535 per invocation); "
                "its image would be wrong: use a GPU, or --backend cpu");
  return out;
}

}  // namespace sst::gpu
