#include "core/manylight/indirect_sampler.h"

namespace sst {

void IndirectSampler::prepare(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters) {
  begin_sampler_inputs(method_id(), lighting.vpls, lighting.clamp_distance, lighting.clamp_per_depth,
                       lighting.context.accel, inputs_);
  build(lighting, timer, counters, inputs_);
}

}  // namespace sst
