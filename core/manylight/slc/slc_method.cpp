// `slc` as the registry lists it: name, description, parameters and factory.
#include "core/manylight/slc/slc_sampler.h"
#include "core/manylight/many_light_method.h"

namespace sst {

MethodInfo slc_method_info() {
  return method_info<SlcParams>("slc",
                                       "stochastic lightcuts (Yuksel 2019): one root-to-leaf light-tree walk per "
                                       "sample, by intensity x cosine bound / distance^2",
                                       [](const SlcParams& p) -> std::unique_ptr<Method> {
                                         return std::make_unique<ManyLightMethod>(p.vpl, params_to_json(p),
                                                                                  std::make_unique<SlcSampler>(p.tree));
                                       });
}

}  // namespace sst
