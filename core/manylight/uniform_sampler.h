// `uniform`: one VPL drawn uniformly, weighted by the VPL count. The baseline every importance
// sampler must beat (METHODS.md §3).
#pragma once
#include "core/manylight/indirect_sampler.h"

namespace sst {

class UniformSampler final : public IndirectSampler {
 public:
  IndirectEstimate estimate(const ManyLightFrame& frame, const ShadingPoint& point, PixelSampler& sampler) const override;
  void gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const override;
};

}  // namespace sst
