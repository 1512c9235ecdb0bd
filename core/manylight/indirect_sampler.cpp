#include "core/manylight/indirect_sampler.h"

#include "core/manylight/indirect_estimate.h"

namespace sst {

void IndirectSampler::prepare(const ManyLightFrame& frame, StageTimer& timer, nlohmann::json& counters) {
  begin_sampler_inputs(method_id(), frame.vpls, frame.clamp_distance, frame.context.accel, inputs_);
  build(frame, timer, counters, inputs_);
}

IndirectEstimate IndirectSampler::estimate(const ShadingPoint& point, PixelSampler& sampler) const {
  return estimate_indirect(inputs_, point, sampler);
}

}  // namespace sst
