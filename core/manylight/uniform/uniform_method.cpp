// `uniform` as the registry lists it: name, description, parameters and factory.
#include "core/manylight/uniform/uniform_sampler.h"
#include "core/manylight/many_light_method.h"
#include "core/manylight/many_light_params.h"

namespace sst {

MethodInfo uniform_method_info() {
  return method_info<VplMethodParams>("uniform", "one VPL per indirect sample, drawn uniformly",
                                      [](const VplMethodParams& p) -> std::unique_ptr<Method> {
                                        return std::make_unique<ManyLightMethod>(p.vpl, params_to_json(p),
                                                                                 std::make_unique<UniformSampler>());
                                      });
}

}  // namespace sst
