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
    // Optimal string alignment distance: Levenshtein plus swapped neighbours at cost 1, the
    // commonest typo ("vlps" is one edit from "vpls", two from "fps").
    std::vector<std::vector<size_t>> d(name.size() + 1, std::vector<size_t>(c.size() + 1));
    for (size_t i = 0; i <= name.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= c.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= name.size(); ++i)
      for (size_t j = 1; j <= c.size(); ++j) {
        d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (name[i - 1] == c[j - 1] ? 0 : 1)});
        if (i > 1 && j > 1 && name[i - 1] == c[j - 2] && name[i - 2] == c[j - 1])
          d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    if (d[name.size()][c.size()] < best_distance) {
      best_distance = d[name.size()][c.size()];
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

std::string range_text(const ParamInfo& p) {
  if (p.type == "float") {
    char max[32];
    std::snprintf(max, sizeof max, "%.6g", p.max_value.get<double>());
    return std::string("a finite number of magnitude at most ") + max;
  }
  if (p.type == "int") return "an integer in " + p.min_value.dump() + ".." + p.max_value.dump();
  return "a " + p.type;
}

std::string to_flag(const std::string& snake_name) {
  std::string flag = snake_name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

}  // namespace sst
