// Reading results.json tolerantly: a missing, null or non-numeric field is a value the caller
// chooses (NaN by default), never an exception, so that tables, reports and the check work on
// partial results and on null metrics (an SSIM of an image smaller than its window).
#pragma once
#include <cmath>
#include <nlohmann/json.hpp>

namespace sst {

// j[key], or null when j is not an object or has no such key.
inline const nlohmann::json& member(const nlohmann::json& j, const char* key) {
  static const nlohmann::json null_value;
  if (!j.is_object()) return null_value;
  auto it = j.find(key);
  return it == j.end() ? null_value : *it;
}

inline double number(const nlohmann::json& j, double fallback = NAN) {
  return j.is_number() ? j.get<double>() : fallback;
}
inline double number(const nlohmann::json& j, const char* key) { return number(member(j, key)); }

}  // namespace sst
