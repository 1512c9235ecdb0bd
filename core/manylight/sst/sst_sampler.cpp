#include "core/manylight/sst/sst_sampler.h"

namespace sst {

ChildWeights sst_weights(const ShadingPoint& point, float eps, SstLobe lobe) {
  bool glossy = lobe == SstLobe::glossy;
  return [&point, eps, glossy](const LightNode& l, const LightNode& r) -> std::array<double, 2> {
    return {sst_node_weight(l, point, eps, glossy), sst_node_weight(r, point, eps, glossy)};
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
