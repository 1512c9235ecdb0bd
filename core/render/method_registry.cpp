#include "core/render/method_registry.h"

#include "core/render/path_tracer.h"

namespace sst {
namespace {
template <class P, class M>
MethodInfo entry(const char* name, const char* description) {
  return {name, description, param_table<P>(), [name](const nlohmann::json& j) -> std::unique_ptr<Method> {
            P params;
            params_from_json(params, j, std::string("method '") + name + "'");
            return std::make_unique<M>(params);
          }};
}
}  // namespace

const std::vector<MethodInfo>& method_registry() {
  static const std::vector<MethodInfo> registry = {
      entry<PathTracerParams, PathTracer>(
          "pt", "unidirectional path tracer, next-event estimation with MIS; PT_n = --max-bounces n"),
  };
  return registry;
}

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
