// `exhaustive`: every VPL, each with its shadow ray. Deterministic given the shading point; the
// VPL ground truth the unbiased samplers converge to (METHODS.md §3).
#pragma once
#include "core/manylight/indirect_sampler.h"

namespace sst {

class ExhaustiveSampler final : public IndirectSampler {
 public:
  IndirectEstimate estimate(const ManyLightFrame& frame, const ShadingPoint& point, PixelSampler& sampler) const override;
  void gpu_inputs(const ManyLightFrame& frame, GpuSamplerInputs& out) const override;
};

// One VPL's contribution at `point`, including visibility (the shadow ray is traced only when
// the unshadowed contribution is non-zero). Shared by every sampler.
vec3 shade_vpl(const ManyLightFrame& frame, const ShadingPoint& point, const Vpl& vpl, uint32_t* shadow_rays);

}  // namespace sst
