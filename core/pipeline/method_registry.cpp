#include "core/pipeline/method_registry.h"

#include "core/manylight/exhaustive_sampler.h"
#include "core/manylight/hybrid_sampler.h"
#include "core/manylight/rtslc_sampler.h"
#include "core/manylight/many_light_method.h"
#include "core/manylight/many_light_params.h"
#include "core/manylight/uniform_sampler.h"
#include "core/manylight/slc_sampler.h"
#include "core/manylight/sst_sampler.h"
#include "core/manylight/tree_method_params.h"
#include "core/pt/path_tracer.h"

namespace sst {
namespace {
// An entry whose parameters P are read from JSON and handed to `make(P)`.
template <class P, class Make>
MethodInfo entry(const char* name, const char* description, Make make) {
  return {name, description, param_table<P>(), [name, make](const nlohmann::json& j) -> std::unique_ptr<Method> {
            P params;
            params_from_json(params, j, std::string("method '") + name + "'");
            return make(params);
          }};
}

template <class P, class M>
MethodInfo entry(const char* name, const char* description) {
  return entry<P>(name, description, [](const P& p) { return std::make_unique<M>(p); });
}

// A VPL method: the shared pipeline around the sampler S built from the parameters.
template <class S>
MethodInfo vpl_method(const char* name, const char* description) {
  return entry<VplMethodParams>(name, description, [](const VplMethodParams& p) -> std::unique_ptr<Method> {
    return std::make_unique<ManyLightMethod>(p.vpl, params_to_json(p), std::make_unique<S>());
  });
}

std::vector<MethodInfo>& mutable_registry() {
  static std::vector<MethodInfo> registry = {
      entry<PathTracerParams, PathTracer>(
          "pt",
          "unidirectional path tracer: next-event estimation with MIS (power heuristic), lights picked by power, close "
          "emissive triangles sampled by solid angle and others by area; the ground truth (PT_n = --max-bounces n)"),
      vpl_method<ExhaustiveSampler>("exhaustive", "every VPL with its shadow ray: the VPL ground truth"),
      vpl_method<UniformSampler>("uniform", "one VPL per indirect sample, drawn uniformly"),
      entry<TreeMethodParams>("slc",
                              "stochastic lightcuts (Yuksel 2019): one root-to-leaf light-tree walk per sample, by "
                              "intensity x cosine bound / distance^2",
                              [](const TreeMethodParams& p) -> std::unique_ptr<Method> {
                                return std::make_unique<ManyLightMethod>(p.vpl, params_to_json(p),
                                                                         std::make_unique<SlcSampler>(p.tree));
                              }),
      entry<SstMethodParams>("sst",
                             "stochastic substitute trees (Tatzgern 2020): the walk stops at a suitable node and "
                             "samples its Gaussian substitute; diffuse and glossy lobes; biased",
                             [](const SstMethodParams& p) -> std::unique_ptr<Method> {
                               return std::make_unique<ManyLightMethod>(p.base.vpl, params_to_json(p),
                                                                        std::make_unique<SstSampler>(p.base.tree, p.sst));
                             }),
      entry<RtslcParams>("rtslc",
                         "real-time stochastic lightcuts (Lin & Yuksel 2020) on the perfect tree: per-block cuts, "
                         "one walk per cut node, min/max-distance weights, interleaving",
                         [](const RtslcParams& p) -> std::unique_ptr<Method> {
                           return std::make_unique<ManyLightMethod>(p.common.vpl, params_to_json(p),
                                                                    std::make_unique<RtslcSampler>(p));
                         }),
      entry<HybridParams>("hybrid",
                          "shallow light cuts over an SST (hybrid thesis, ch. 5): per-block cuts blended "
                          "stochastically between neighbours, mock cuts, substitutes; biased",
                          [](const HybridParams& p) -> std::unique_ptr<Method> {
                            return std::make_unique<ManyLightMethod>(p.common.vpl, params_to_json(p),
                                                                     std::make_unique<HybridSampler>(p));
                          }),
  };
  return registry;
}

MethodInfo& registry_entry(const std::string& name) {
  for (MethodInfo& m : mutable_registry())
    if (m.name == name) return m;
  throw Error("ScopedMethodOverride: no method '" + name + "' to replace");
}

}  // namespace

const std::vector<MethodInfo>& method_registry() { return mutable_registry(); }

ScopedMethodOverride::ScopedMethodOverride(MethodInfo replacement) {
  MethodInfo& entry = registry_entry(replacement.name);
  original_ = entry;
  entry = std::move(replacement);
}

ScopedMethodOverride::~ScopedMethodOverride() { registry_entry(original_.name) = original_; }

const MethodInfo& find_method(const std::string& name) {
  std::vector<std::string> names;
  for (const MethodInfo& m : method_registry()) {
    if (m.name == name) return m;
    names.push_back(m.name);
  }
  throw Error("unknown method '" + name + "' (did you mean '" + nearest_name(name, names) + "'?)");
}

std::unique_ptr<Method> create_method(const std::string& name, const nlohmann::json& params) {
  return find_method(name).create(params);
}

}  // namespace sst
