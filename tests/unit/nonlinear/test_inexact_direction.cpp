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

TEST(TerminalForcing, RaisesTheToleranceToWhatNewtonsStoppingTestReads) {
  // A right side far above Newton's tolerance keeps the forcing term.
  EXPECT_DOUBLE_EQ(terminal_forcing(1e-4, 0.5e-9, 1.0), 1e-4);
  // block-strips level 2, the second solve of a pressing step: right side 8.4e-4, Newton's
  // tolerance 1e-6 x 8.76 (half of it terminal): 5.2e-3 of the right side is enough.
  EXPECT_DOUBLE_EQ(terminal_forcing(1e-4, 0.5 * 8.76e-6, 8.4e-4), 0.5 * 8.76e-6 / 8.4e-4);
  // Never looser than kMaxTerminalForcing, and a looser forcing term stays.
  EXPECT_DOUBLE_EQ(terminal_forcing(1e-4, 1.0, 2.0), kMaxTerminalForcing);
  EXPECT_DOUBLE_EQ(terminal_forcing(0.3, 1.0, 2.0), 0.3);
}

TEST(TerminalForcing, UnchangedWithoutATerminalResidualARightSideOrATolerance) {
  EXPECT_DOUBLE_EQ(terminal_forcing(1e-4, 0.0, 1e-6), 1e-4) << "a pending lifting has no terminal residual";
  EXPECT_DOUBLE_EQ(terminal_forcing(1e-4, 1e-6, 0.0), 1e-4);
  EXPECT_DOUBLE_EQ(terminal_forcing(0.0, 1e-6, 1e-6), 0.0) << "a direct backend has no tolerance to raise";
}

}  // namespace
}  // namespace stiction::nonlinear
