// Statistics for tests that must not flake: chi-square against a critical value at a tiny
// significance level (fixed seeds make each test deterministic; the level makes a real bug,
// not chance, the likely reason for a failure).
#pragma once
#include <cmath>
#include <vector>

namespace sst::test {

// Pearson's statistic; bins whose expected count is below 5 are pooled into one.
inline double chi_square_statistic(const std::vector<double>& observed, const std::vector<double>& expected,
                                   int* degrees_of_freedom) {
  double chi2 = 0.0, pooled_o = 0.0, pooled_e = 0.0;
  int bins = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5.0) {
      pooled_o += observed[i];
      pooled_e += expected[i];
      continue;
    }
    chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pooled_e >= 5.0) {
    chi2 += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++bins;
  } else if (pooled_o > 0.0 && pooled_e == 0.0) {
    chi2 = INFINITY;  // observed where nothing may be: a hard failure
  }
  *degrees_of_freedom = std::max(1, bins - 1);
  return chi2;
}

// Upper critical value of the chi-square distribution at significance 1e-6 (Wilson-Hilferty).
inline double chi_square_critical_1e6(int dof) {
  const double z = 4.753;  // standard normal quantile of 1 - 1e-6
  double k = double(dof);
  double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

}  // namespace sst::test
