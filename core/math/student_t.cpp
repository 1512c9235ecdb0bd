#include "core/math/student_t.h"

#include <cmath>

namespace sst {
namespace {

// The continued fraction of I_x(a, b), which converges fast for x < (a + 1) / (a + b + 2).
double beta_continued_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  constexpr double kEpsilon = 1e-14;
  auto not_tiny = [](double v) { return std::abs(v) < kTiny ? kTiny : v; };
  double c = 1.0;
  double d = 1.0 / not_tiny(1.0 - (a + b) * x / (a + 1.0));
  double h = d;
  for (int m = 1; m <= 500; ++m) {
    // The even step of the fraction, then the odd one.
    double numerator = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m));
    d = 1.0 / not_tiny(1.0 + numerator * d);
    c = not_tiny(1.0 + numerator / c);
    h *= d * c;
    numerator = -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1));
    d = 1.0 / not_tiny(1.0 + numerator * d);
    c = not_tiny(1.0 + numerator / c);
    const double step = d * c;
    h *= step;
    if (std::abs(step - 1.0) < kEpsilon) break;
  }
  return h;
}

}  // namespace

double regularized_incomplete_beta(double a, double b, double x) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double log_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(log_front);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_continued_fraction(a, b, x) / a;
  return 1.0 - front * beta_continued_fraction(b, a, 1.0 - x) / b;
}

double student_t_two_sided_p(double t, double df) {
  if (std::isnan(t)) return NAN;
  if (std::isinf(t)) return 0.0;
  return regularized_incomplete_beta(0.5 * df, 0.5, df / (df + t * t));
}

double student_t_upper_p(double t, double df) {
  const double two_sided = student_t_two_sided_p(t, df);
  return t >= 0.0 ? 0.5 * two_sided : 1.0 - 0.5 * two_sided;
}

}  // namespace sst
