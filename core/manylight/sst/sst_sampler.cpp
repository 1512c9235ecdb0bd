#include "core/manylight/sst/sst_sampler.h"

#include <cmath>
#include <string>

#include "core/util/error.h"
#include "core/util/params.h"

namespace sst {

void validate(const SstParams& p) {
  // A negative floor would let the weights' distance reach zero and below; NaN would make every
  // comparison false and the walk arbitrary.
  if (!(p.distance_floor >= 0.0f) || !std::isfinite(p.distance_floor))
    throw Error("sst: parameter 'distance_floor' must be finite and >= 0 (got " + nlohmann::json(shortest_decimal(p.distance_floor)).dump() + ")");
}

ChildWeights sst_weights(const ShadingPoint& point, float eps, SstLobe lobe, float floor_fraction) {
  SstWalkBound bound = sst_walk_bound(point, lobe == SstLobe::glossy, eps, floor_fraction);
  return [&point, bound](const LightNode& l, const LightNode& r) -> std::array<double, 2> {
    vec2 w = sst_child_weights(l, r, point, bound);
    return {w.x, w.y};
  };
}

StopRule sst_stop_rule(SstLobe lobe, bool substitutes) {
  if (lobe == SstLobe::glossy || !substitutes) return stop_at_leaves;
  return [](const LightNode& n) { return n.is_leaf() || n.suitable(); };
}

void SstSampler::build(const VplLighting& lighting, StageTimer& timer, nlohmann::json& counters, SamplerInputs& inputs) {
  TreeSamplerBase::build(lighting, timer, counters, inputs);
  inputs.params.sst_eps = sst_.distance_floor * tree_.length_scale;
  inputs.params.sst_substitutes = sst_.substitutes ? 1u : 0u;
}

}  // namespace sst
