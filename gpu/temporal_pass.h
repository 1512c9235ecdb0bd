// Temporal reuse on the GPU: core/temporal/temporal_accumulate.h's kernel over the frame, as
// core/temporal/temporal_reuse.h runs it on the CPU, with the GPU time of its dispatch.
#pragma once
#include <vector>

#include "core/temporal/temporal_layout.h"
#include "gpu/vulkan_context.h"

namespace sst::gpu {

struct TemporalHistory {
  std::vector<TemporalTexel> texels;
  double gpu_ms = 0.0;
};

// The new history from the frame's inputs and the previous history (empty: the first frame).
TemporalHistory temporal_accumulate(const VulkanContext& context, const std::vector<TemporalInput>& input,
                                    const std::vector<TemporalTexel>& history, const TemporalPush& push);

}  // namespace sst::gpu
