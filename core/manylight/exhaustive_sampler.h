// `exhaustive`: every VPL, each with its shadow ray (exhaustive_estimate.h). Deterministic given
// the shading point; the VPL ground truth the unbiased samplers converge to (METHODS.md §3).
#pragma once
#include "core/manylight/indirect_sampler.h"

namespace sst {

class ExhaustiveSampler final : public IndirectSampler {
 protected:
  uint32_t method_id() const override { return ML_METHOD_EXHAUSTIVE; }
};

}  // namespace sst
