// Zolotarev's approximation of x^-1/2 (zolotarev.hpp), checked directly against x^-1/2 on a
// grid ten times finer than the one that sets its scale.
#include <gtest/gtest.h>

#include <cmath>

#include "zolotarev.hpp"

using stiction::solvers::zolotarev_inverse_square_root;

namespace {

double relative_error(const stiction::solvers::InverseSquareRootApproximation& a, double x) {
  double sum = a.constant;
  for (size_t k = 0; k < a.weight.size(); ++k) sum += a.weight[k] / (x + a.shift[k]);
  return std::abs(sum * std::sqrt(x) - 1);
}

}  // namespace

// Spans of the contact zones' spectra (1e4 to 1e8); the trapezoidal rule in log x, the
// classical alternative, needs 11 to 18 terms for 1e-2 on these spans.
TEST(Zolotarev, InverseSquareRootMeetsItsToleranceWithFewTerms) {
  struct Case {
    double span, tolerance;
    int at_most_terms;
  };
  for (const Case c : {Case{1.0, 1e-2, 1}, Case{1e4, 1e-2, 4}, Case{1e6, 1e-2, 5}, Case{1e8, 1e-2, 6},
                       Case{1e8, 1e-3, 9}}) {
    const double x_low = 0.37, x_high = x_low * c.span;
    const auto a = zolotarev_inverse_square_root(x_low, x_high, c.tolerance);
    EXPECT_LE(static_cast<int>(a.weight.size()), c.at_most_terms) << "span " << c.span;
    EXPECT_LE(a.error, c.tolerance) << "span " << c.span;
    EXPECT_GT(a.constant, 0);
    for (size_t k = 0; k < a.weight.size(); ++k) {
      EXPECT_GT(a.weight[k], 0);  // positive weights and shifts: SPD shifted systems, no cancellation
      EXPECT_GT(a.shift[k], 0);
    }
    double worst = 0;
    for (int i = 0; i <= 20000; ++i) worst = std::max(worst, relative_error(a, x_low * std::pow(c.span, i / 20000.0)));
    EXPECT_LE(worst, 1.01 * a.error + 1e-14) << "span " << c.span;
    EXPECT_GE(worst, 0.99 * a.error) << "span " << c.span;  // the reported error is the true one
  }
}

// One term fewer than chosen misses the tolerance: the degree is the smallest that meets it.
TEST(Zolotarev, ChoosesTheSmallestDegree) {
  const auto a = zolotarev_inverse_square_root(1.0, 1e6, 1e-3);
  ASSERT_GE(a.weight.size(), 2u);
  const auto fewer = zolotarev_inverse_square_root(1.0, 1e6, 1e-3, static_cast<int>(a.weight.size()) - 1);
  EXPECT_GT(fewer.error, 1e-3);
  EXPECT_LE(a.error, 1e-3);
}

TEST(Zolotarev, RefusesAnEmptyOrNegativeInterval) {
  EXPECT_THROW(zolotarev_inverse_square_root(0.0, 1.0, 1e-2), std::invalid_argument);
  EXPECT_THROW(zolotarev_inverse_square_root(2.0, 1.0, 1e-2), std::invalid_argument);
}
