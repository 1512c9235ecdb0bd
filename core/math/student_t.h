// Student's t distribution, for the CI check's two-sample tests (core/eval/distribution_check.h).
#pragma once

namespace sst {

// I_x(a, b), the regularized incomplete beta function, for a, b > 0 and x in [0, 1]
// (continued fraction by the modified Lentz method; relative error about 1e-12).
double regularized_incomplete_beta(double a, double b, double x);

// P(|T| >= |t|) for T with `df` > 0 degrees of freedom: the two-sided p-value of t.
double student_t_two_sided_p(double t, double df);

// P(T >= t): the one-sided p-value of t.
double student_t_upper_p(double t, double df);

}  // namespace sst
