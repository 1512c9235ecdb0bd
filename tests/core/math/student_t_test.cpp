#include "core/math/student_t.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sst {
namespace {

TEST(StudentT, TwoSidedPValuesMatchTables) {
  // R: 2 * pt(-|t|, df).
  EXPECT_NEAR(student_t_two_sided_p(2.0, 10.0), 0.07338803, 1e-7);
  EXPECT_NEAR(student_t_two_sided_p(-2.0, 10.0), 0.07338803, 1e-7);
  EXPECT_NEAR(student_t_two_sided_p(1.0, 1.0), 0.5, 1e-12);  // Cauchy
  EXPECT_NEAR(student_t_two_sided_p(5.0, 29.0) / 2.5366316e-05, 1.0, 1e-5);
  EXPECT_NEAR(student_t_two_sided_p(0.0, 7.0), 1.0, 1e-12);
  // Many degrees of freedom: the normal's 2 * (1 - Phi(6)).
  EXPECT_NEAR(student_t_two_sided_p(6.0, 1e7) / 1.973175e-09, 1.0, 1e-4);
}

TEST(StudentT, UpperPIsHalfTheTwoSidedOnTheRightAndItsComplementOnTheLeft) {
  EXPECT_NEAR(student_t_upper_p(2.0, 10.0), 0.03669402, 1e-7);
  EXPECT_NEAR(student_t_upper_p(-2.0, 10.0), 1.0 - 0.03669402, 1e-7);
  EXPECT_EQ(student_t_upper_p(INFINITY, 3.0), 0.0);
  EXPECT_TRUE(std::isnan(student_t_two_sided_p(NAN, 3.0)));
}

TEST(StudentT, IncompleteBetaIsTheUniformCdfForOneOne) {
  for (double x : {0.0, 0.1, 0.5, 0.93, 1.0}) EXPECT_NEAR(regularized_incomplete_beta(1.0, 1.0, x), x, 1e-12);
  // I_x(a, b) = 1 - I_{1-x}(b, a).
  EXPECT_NEAR(regularized_incomplete_beta(2.5, 7.0, 0.3), 1.0 - regularized_incomplete_beta(7.0, 2.5, 0.7), 1e-12);
}

}  // namespace
}  // namespace sst
