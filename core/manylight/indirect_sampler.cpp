#include "core/manylight/indirect_sampler.h"

namespace sst {

void IndirectSampler::prepare(const ManyLightFrame& frame, StageTimer& timer, nlohmann::json& counters) {
  begin_sampler_inputs(method_id(), frame.vpls, frame.clamp_distance, frame.context.accel, inputs_);
  build(frame, timer, counters, inputs_);
}

}  // namespace sst
