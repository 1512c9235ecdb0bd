// The registry of methods: each method's MethodInfo (core/render/method.h), `pt` first and then
// the VPL methods in the order of their list (core/manylight/many_light_methods.h), from which the
// registry is generated, then gi10. The CLIs build their flags from the parameter tables.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/render/method.h"

namespace sst {

const std::vector<MethodInfo>& method_registry();

// Replaces the registry entry of the same name while it lives, then restores it. For tests only:
// they inject deliberately broken methods to show that the metrics check catches them. Not
// thread-safe; nothing may render concurrently.
class ScopedMethodOverride {
 public:
  explicit ScopedMethodOverride(MethodInfo replacement);
  ~ScopedMethodOverride();
  ScopedMethodOverride(const ScopedMethodOverride&) = delete;
  ScopedMethodOverride& operator=(const ScopedMethodOverride&) = delete;

 private:
  MethodInfo original_;
};
const MethodInfo& find_method(const std::string& name);  // throws sst::Error naming the nearest
// The one factory: the method `name` with `params` (a JSON object of that method's parameters).
std::unique_ptr<Method> create_method(const std::string& name, const nlohmann::json& params);

}  // namespace sst
