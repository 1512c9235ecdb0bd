#include "core/util/params.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace sst {

std::string nearest_name(const std::string& name, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = SIZE_MAX;
  for (const auto& c : candidates) {
    // Levenshtein distance by dynamic programming over one row.
    std::vector<size_t> row(c.size() + 1);
    for (size_t j = 0; j <= c.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= name.size(); ++i) {
      size_t diagonal = row[0];
      row[0] = i;
      for (size_t j = 1; j <= c.size(); ++j) {
        size_t substitution = diagonal + (name[i - 1] == c[j - 1] ? 0 : 1);
        diagonal = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
      }
    }
    if (row[c.size()] < best_distance) {
      best_distance = row[c.size()];
      best = c;
    }
  }
  return best;
}

double shortest_decimal(float value) {
  if (!std::isfinite(value)) return double(value);
  char text[32];
  for (int digits = 6; digits <= 9; ++digits) {
    std::snprintf(text, sizeof(text), "%.*g", digits, double(value));
    double parsed = std::strtod(text, nullptr);
    if (float(parsed) == value) return parsed;
  }
  return double(value);
}

std::string to_flag(const std::string& snake_name) {
  std::string flag = snake_name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

}  // namespace sst
