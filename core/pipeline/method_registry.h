// The registry of methods: name -> description, parameter table, factory. Adding a method means
// adding one entry in method_registry.cpp; the CLIs build their flags from the tables.
#pragma once
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/render/method.h"
#include "core/util/params.h"

namespace sst {

struct MethodInfo {
  std::string name;
  std::string description;
  std::vector<ParamInfo> params;
  // Builds the method from its parameters; unknown keys are an error naming the key.
  std::function<std::unique_ptr<Method>(const nlohmann::json& params)> create;
};

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
