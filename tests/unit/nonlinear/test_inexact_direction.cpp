// When an unconverged Krylov solve still gives a Newton update (nonlinear/inexact_direction).
#include <gtest/gtest.h>

#include <limits>

#include "nonlinear/inexact_direction.hpp"

namespace stiction::nonlinear {
namespace {

LinearSolveStats stagnated(double initial, double final, double rtol = 1e-4) {
  LinearSolveStats s;
  s.converged = false;
  s.reason = "DIVERGED_STAGNATION";
  s.initial_residual = initial;
  s.final_residual = final;
  s.extra["ksp_rtol"] = rtol;
  return s;
}

TEST(InexactDirection, WithinTheForcingFactorOfTheTolerance) {
  // rtol 1e-4, factor 10: up to 1e-3 of the right side, whatever Newton's tolerance.
  EXPECT_TRUE(usable_direction(stagnated(2.0, 1.9e-3), 0.0));
  EXPECT_TRUE(usable_direction(stagnated(2.0, 2.0e-3), 0.0));
  EXPECT_FALSE(usable_direction(stagnated(2.0, 2.1e-3), 0.0));
  EXPECT_FALSE(usable_direction(stagnated(2.0, 2.1e-3, 1e-5), 0.0));
}

TEST(InexactDirection, BelowWhatNewtonsStoppingTestAsks) {
  // The crossed tubes' last system at t = 75.5 (level 1): right side 9.58e-6, stopped at
  // 1.416e-3 of it; Newton's tolerances there 3.83e-5 (free) and 1.1e-7 (contact).
  const LinearSolveStats s = stagnated(9.58e-6, 1.416e-3 * 9.58e-6);
  EXPECT_FALSE(usable_direction(s, 0.0)) << "beyond the forcing factor alone";
  EXPECT_TRUE(usable_direction(s, 0.5 * 1.1e-7));
  EXPECT_FALSE(usable_direction(s, 0.5 * 1e-8)) << "a tighter Newton tolerance refuses it";
}

TEST(InexactDirection, NeverWithoutATolerancePositiveRightSideOrFiniteResidual) {
  LinearSolveStats no_rtol = stagnated(1.0, 1e-9);
  no_rtol.extra.clear();
  EXPECT_FALSE(usable_direction(no_rtol, 1.0));
  EXPECT_FALSE(usable_direction(stagnated(0.0, 0.0), 1.0));
  EXPECT_FALSE(usable_direction(stagnated(1.0, std::numeric_limits<double>::quiet_NaN()), 1.0));
  EXPECT_FALSE(usable_direction(stagnated(1.0, std::numeric_limits<double>::infinity()), 1.0));
}

}  // namespace
}  // namespace stiction::nonlinear
