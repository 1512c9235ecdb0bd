// `hybrid` as the registry lists it: name, description, parameters and factory.
#include "core/manylight/hybrid/hybrid_sampler.h"
#include "core/manylight/many_light_method.h"

namespace sst {

MethodInfo hybrid_method_info() {
  return method_info<HybridParams>("hybrid",
                                   "shallow light cuts over an SST (hybrid thesis, ch. 5): per-block cuts blended "
                                   "stochastically between neighbours, mock cuts, substitutes; biased",
                                   [](const HybridParams& p) -> std::unique_ptr<Method> {
                                     return std::make_unique<ManyLightMethod>(p.tree_method.vpl, params_to_json(p),
                                                                              std::make_unique<HybridSampler>(p));
                                   });
}

}  // namespace sst
