// gi10 (GI-1.0) on the Vulkan backend: the frame driver of core/gi10/gi10_method.h with its stages
// dispatched to gpu/shaders/gi10.comp, one invocation per element, on buffers that live on the
// device between frames; the direct pass is pt's (gpu/path_trace_pass.h) with max_bounces 0.
#pragma once
#include <memory>
#include <vector>

#include "core/gi10/gi10_method.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_method.h"

namespace sst::gpu {

class VulkanGi10 final : public VulkanMethod, private Gi10Executor {
 public:
  explicit VulkanGi10(Gi10Method& method) : method_(method) {}
  FrameOutput render(const RenderContext& context, const GpuRenderContext& gpu, StageTimer& timer) override;
  // The caches live on the device: before a new device context (a pose change) they move to the
  // host and come back with the next frame, so the frames go on as on the CPU.
  void release_device() override;
  std::vector<uint8_t> save_history() const override;
  void restore_history(std::span<const uint8_t> bytes, bool posed) override;

 private:
  void allocate(const Gi10Sizes& sizes) override;
  void begin_frame(const RenderContext& context, const glsl::Gi10Frame& frame) override;
  double run(uint32_t stage, uint32_t pass, uint32_t count) override;
  void clear_counters() override;
  std::vector<uint32_t> counters() override;
  void read_irradiance(std::vector<glm::vec4>& denoised, std::vector<glm::vec4>& raw) override;
  void read_pixels(std::vector<glsl::Gi10Pixel>& pixels) override;
  void write_feedback(const std::vector<glm::vec4>& image) override;
  FrameOutput direct(const RenderContext& context, StageTimer& timer) override;
  std::vector<std::span<const uint8_t>> buffers() const override;
  std::vector<std::span<uint8_t>> buffers() override;
  // The buffers after the frame constants, as bytes in place, for `self` const or not.
  template <class Byte, class Self>
  static std::vector<std::span<Byte>> byte_views(Self& self);
  // The pipeline of a shader build of gpu/shaders/gi10.comp (GI10_SHADER_BUILDS).
  std::unique_ptr<ComputePipeline> make_stage_pipeline(uint32_t build) const;

  Gi10Method& method_;
  const GpuRenderContext* gpu_ = nullptr;
  // One per shader build (GI10_SHADER_BUILDS): the stages' with the first frame, SHADE's others
  // when a frame needs them.
  std::vector<std::unique_ptr<ComputePipeline>> pipelines_;
  std::unique_ptr<ComputePipeline> direct_pipeline_;
  Gi10Sizes sizes_;
  uint32_t parity_ = 0;
  uint32_t shade_build_ = GI10_STAGE_SHADE;  // the frame's build of SHADE (gi10_shade_build)
  // In binding order after the scene's: frame constants, then the buffers of gi10_stages.h.
  std::vector<std::unique_ptr<GpuBuffer>> buffers_;
  std::vector<const GpuBuffer*> bound_;
  // Gi10Renderer::save's bytes waiting for a device context (empty: none).
  std::vector<uint8_t> parked_;
};

}  // namespace sst::gpu
