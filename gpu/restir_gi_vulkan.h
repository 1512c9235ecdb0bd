// RestirGi (core/restir/restir_gi.h) on the Vulkan backend: the direct light and AOVs by pt.comp
// with max_bounces 0 (gpu/path_trace_pass.h), then ReSTIR GI's rounds (gpu/restir_pass.h) into
// the indirect layer, as the CPU's RestirGi::render does.
#pragma once
#include <memory>

#include "core/restir/restir_gi.h"
#include "gpu/restir_pass.h"
#include "gpu/vulkan_method.h"

namespace sst::gpu {

class VulkanRestirGi final : public VulkanMethod {
 public:
  explicit VulkanRestirGi(const RestirGi& method) : method_(method) {}
  FrameOutput render(const RenderContext& context, const GpuRenderContext& gpu, StageTimer& timer) override;
  void release_device() override;
  std::vector<uint8_t> save_history() const override;
  void restore_history(std::span<const uint8_t> bytes, bool posed) override;

 private:
  const RestirGi& method_;
  std::unique_ptr<ComputePipeline> direct_;
  std::unique_ptr<RestirPipelines> pipelines_;
  std::unique_ptr<GpuRestirHistory> history_;
};

}  // namespace sst::gpu
