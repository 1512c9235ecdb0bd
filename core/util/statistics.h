// Summaries of repeated measurements, one definition for every record: the median (mean of
// the two middle values for an even count) and the {"median", "min", "max"} object of timings.
#pragma once
#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

namespace sst {

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// {"median": .., "min": .., "max": ..}; `v` must not be empty.
inline nlohmann::json median_min_max(const std::vector<double>& v) {
  return {{"median", median(v)}, {"min", *std::min_element(v.begin(), v.end())},
          {"max", *std::max_element(v.begin(), v.end())}};
}

}  // namespace sst
