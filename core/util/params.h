// Parameter structs, yocto-gl style: each struct lists its fields once, in a member template
//   template <class V> void visit(V&& v) { v("spp", spp, "samples per pixel"); ... }
// and everything else (JSON in and out, CLI flags, the parameter tables in --help and docs,
// unknown-key errors) is derived from that one list, so a field cannot be forgotten in one of
// them. Names are snake_case; CLI flags are the same names with '-' for '_'.
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <type_traits>
#include <vector>

#include "core/util/error.h"

namespace sst {

// The closest of `candidates` to `name` (Levenshtein distance), for "did you mean" messages.
std::string nearest_name(const std::string& name, const std::vector<std::string>& candidates);
std::string to_flag(const std::string& snake_name);  // "max_bounces" -> "max-bounces"

struct ParamInfo {
  std::string name, type, help;
  nlohmann::json default_value;
  // The values the field's C++ type holds (null for non-numbers), so that a flag or key is
  // refused when it does not fit instead of being narrowed ("--vpls 9999999999999" is not 1316134911).
  nlohmann::json min_value, max_value;
};

// The range of a numeric field's type: [lowest, max] of integers; [-FLT_MAX, FLT_MAX] of floats
// (a double beyond it would become Inf, or be undefined, when narrowed).
template <class T>
std::pair<nlohmann::json, nlohmann::json> value_range() {
  if constexpr (std::is_same_v<T, bool> || !std::is_arithmetic_v<T>)
    return {nullptr, nullptr};
  else
    return {std::numeric_limits<T>::lowest(), std::numeric_limits<T>::max()};
}

// Whether a JSON number fits the type T without narrowing (integers) or overflow (floats), and
// is finite. Non-numbers are false.
template <class T>
bool fits(const nlohmann::json& v) {
  if constexpr (std::is_integral_v<T>) {
    if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(std::numeric_limits<T>::max());
    if (!v.is_number_integer()) return false;
    int64_t i = v.get<int64_t>();
    if constexpr (std::is_unsigned_v<T>) return i >= 0 && uint64_t(i) <= uint64_t(std::numeric_limits<T>::max());
    else return i >= int64_t(std::numeric_limits<T>::lowest()) && i <= int64_t(std::numeric_limits<T>::max());
  } else if constexpr (std::is_floating_point_v<T>) {
    if (!v.is_number()) return false;
    double d = v.get<double>();
    return std::isfinite(d) && std::fabs(d) <= double(std::numeric_limits<T>::max());
  } else {
    return false;
  }
}

// What a parameter accepts, for messages: "an integer in -2147483648..2147483647", "a finite number
// of magnitude at most 3.40282e+38".
std::string range_text(const ParamInfo& p);

// The shortest decimal that reads back as the same float, so 0.01f is written 0.01, not
// 0.009999999776 (floats go to JSON through double).
double shortest_decimal(float value);

template <class P>
nlohmann::json params_to_json(const P& params) {
  nlohmann::json j = nlohmann::json::object();
  const_cast<P&>(params).visit([&](const char* name, auto& field, const char*) {
    if constexpr (std::is_same_v<std::decay_t<decltype(field)>, float>)
      j[name] = shortest_decimal(field);
    else
      j[name] = field;
  });
  return j;
}

template <class P>
std::vector<std::string> param_names() {
  std::vector<std::string> names;
  P p;
  p.visit([&](const char* name, auto&, const char*) { names.push_back(name); });
  return names;
}

template <class P>
std::vector<ParamInfo> param_table() {
  std::vector<ParamInfo> table;
  P p;
  p.visit([&](const char* name, auto& field, const char* help) {
    using T = std::decay_t<decltype(field)>;
    std::string type = std::is_same_v<T, bool>             ? "bool"
                       : std::is_integral_v<T>             ? "int"
                       : std::is_floating_point_v<T>       ? "float"
                       : std::is_same_v<T, std::string>    ? "string"
                                                           : "value";
    nlohmann::json value = field;
    if constexpr (std::is_same_v<T, float>) value = shortest_decimal(field);
    auto [lo, hi] = value_range<T>();
    table.push_back({name, type, help, value, lo, hi});
  });
  return table;
}

// Reads the keys of `j` that belong to P into `params`. Keys of P absent from `j` keep their
// values. A key in `j` that P does not have is an error naming it and the nearest valid key,
// unless `allow_other_keys` (when one JSON object feeds several parameter structs).
// `context` names where the JSON came from (a file, "--method pt") for the message.
template <class P>
void params_from_json(P& params, const nlohmann::json& j, const std::string& context,
                      bool allow_other_keys = false) {
  if (j.is_null()) return;  // no parameters given
  if (!j.is_object()) throw Error(context + ": expected a JSON object of parameters");
  if (!allow_other_keys) {
    auto names = param_names<P>();
    for (const auto& [key, value] : j.items()) {
      if (std::find(names.begin(), names.end(), key) == names.end())
        throw Error(context + ": unknown parameter '" + key + "' (did you mean '" +
                    nearest_name(key, names) + "'?)");
    }
  }
  params.visit([&](const char* name, auto& field, const char*) {
    auto it = j.find(name);
    if (it == j.end()) return;
    using T = std::decay_t<decltype(field)>;
    try {
      if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
        if (!it->is_number_integer() && !it->is_number_unsigned())
          throw Error("not an integer");
        if (!fits<T>(*it))
          throw Error("out of range (" + std::to_string(std::numeric_limits<T>::lowest()) + ".." +
                      std::to_string(std::numeric_limits<T>::max()) + ")");
      } else if constexpr (std::is_floating_point_v<T>) {
        if (!it->is_number()) throw Error("not a number");
        if (!fits<T>(*it)) throw Error("not a finite number in the range of a float");
      } else if constexpr (std::is_same_v<T, bool>) {
        if (!it->is_boolean()) throw Error("not true/false");
      } else if constexpr (std::is_same_v<T, std::string>) {
        if (!it->is_string()) throw Error("not a string");
      }
      field = it->template get<T>();
    } catch (const std::exception& e) {
      throw Error(context + ": parameter '" + name + "' has value " + it->dump() + ": " + e.what());
    }
  });
}

}  // namespace sst
