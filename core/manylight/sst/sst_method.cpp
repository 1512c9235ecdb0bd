// `sst` as the registry lists it: name, description, parameters and factory.
#include "core/manylight/sst/sst_sampler.h"
#include "core/manylight/many_light_method.h"

namespace sst {

MethodInfo sst_method_info() {
  return method_info<SstMethodParams>("sst",
                                      "stochastic substitute trees (Tatzgern 2020): the walk stops at a suitable node "
                                      "and samples its Gaussian substitute; diffuse and glossy lobes; biased",
                                      [](const SstMethodParams& p) -> std::unique_ptr<Method> {
                                        validate(p.sst);
                                        return std::make_unique<ManyLightMethod>(
                                            p.tree_method.vpl, params_to_json(p), std::make_unique<SstSampler>(p.tree_method.tree, p.sst));
                                      });
}

}  // namespace sst
