// `exhaustive` as the registry lists it: name, description, parameters and factory.
#include "core/manylight/exhaustive/exhaustive_sampler.h"
#include "core/manylight/many_light_method.h"
#include "core/manylight/many_light_params.h"

namespace sst {

MethodInfo exhaustive_method_info() {
  return method_info<VplMethodParams>("exhaustive", "every VPL with its shadow ray: the VPL ground truth",
                                      [](const VplMethodParams& p) -> std::unique_ptr<Method> {
                                        return std::make_unique<ManyLightMethod>(p.vpl, params_to_json(p),
                                                                                 std::make_unique<ExhaustiveSampler>());
                                      });
}

}  // namespace sst
