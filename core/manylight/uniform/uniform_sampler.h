// `uniform`: one VPL drawn uniformly, weighted by the VPL count (uniform_estimate.h). The baseline
// every importance sampler must beat (docs/design/methods.md).
#pragma once
#include "core/manylight/indirect_sampler.h"
#include "core/manylight/uniform/uniform_estimate.h"

namespace sst {

class UniformSampler final : public IndirectSampler {
 public:
  IndirectEstimate estimate(const ShadingPoint& point, PixelSampler& sampler) const override {
    return estimate_uniform(inputs(), point, sampler);
  }

 protected:
  uint32_t method_id() const override { return ML_METHOD_uniform; }
};

}  // namespace sst
