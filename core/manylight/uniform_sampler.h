// `uniform`: one VPL drawn uniformly, weighted by the VPL count (uniform_estimate.h). The baseline
// every importance sampler must beat (METHODS.md §3).
#pragma once
#include "core/manylight/indirect_sampler.h"

namespace sst {

class UniformSampler final : public IndirectSampler {
 protected:
  uint32_t method_id() const override { return ML_METHOD_UNIFORM; }
};

}  // namespace sst
