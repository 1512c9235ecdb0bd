#include "core/pipeline/method_registry.h"

#include "core/gi10/gi10_method.h"
#include "core/manylight/many_light_method.h"
#include "core/manylight/many_light_methods.h"
#include "core/pt/pt_method.h"
#include "core/restir/restir_gi.h"

namespace sst {
namespace {

std::vector<MethodInfo> all_methods() {
  std::vector<MethodInfo> methods = {pt_method_info()};
  // The name a method's folder gives its MethodInfo must be its name in the list.
  auto add = [&methods](MethodInfo info, const char* listed_as) {
    if (info.name != listed_as)
      throw Error("method registry: " + std::string(listed_as) + "_method_info() names its method '" + info.name + "'");
    methods.push_back(std::move(info));
  };
#define ADD_MANY_LIGHT_METHOD(name, id) add(name##_method_info(), #name);
  SST_MANY_LIGHT_METHODS(ADD_MANY_LIGHT_METHOD)
#undef ADD_MANY_LIGHT_METHOD
  add(gi10_method_info(), "gi10");
  add(restir_gi_method_info(), "restir_gi");
  return methods;
}

std::vector<MethodInfo>& mutable_registry() {
  static std::vector<MethodInfo> registry = all_methods();
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
