// `exhaustive`: every VPL, each with its shadow ray (exhaustive_estimate.h). Deterministic given
// the shading point; the VPL ground truth the unbiased samplers converge to (docs/design/methods.md).
#pragma once
#include "core/manylight/exhaustive/exhaustive_estimate.h"
#include "core/manylight/indirect_sampler.h"

namespace sst {

class ExhaustiveSampler final : public IndirectSampler {
 public:
  IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const override {
    return estimate_exhaustive(inputs(), point, sampler);
  }

 protected:
  uint32_t method_id() const override { return ML_METHOD_exhaustive; }
};

}  // namespace sst
