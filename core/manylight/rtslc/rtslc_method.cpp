// `rtslc` as the registry lists it: name, description, parameters and factory.
#include "core/manylight/rtslc/rtslc_sampler.h"
#include "core/manylight/many_light_method.h"

namespace sst {

MethodInfo rtslc_method_info() {
  return method_info<RtslcParams>("rtslc",
                                  "real-time stochastic lightcuts (Lin & Yuksel 2020) on the perfect tree: per-block "
                                  "cuts, one walk per cut node, min/max-distance weights, interleaving",
                                  [](const RtslcParams& p) -> std::unique_ptr<Method> {
                                    return std::make_unique<ManyLightMethod>(p.tree_method.vpl, params_to_json(p),
                                                                             std::make_unique<RtslcSampler>(p));
                                  });
}

}  // namespace sst
