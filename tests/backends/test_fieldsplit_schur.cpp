// fieldsplit-schur sets up its splits' solvers (the displacement GAMG, the Schur
// complement's factorisation) in setup(), where PCFIELDSPLIT alone would leave them to the
// first application: the set-up reports the AMG's operator complexity, and the solve the
// same converged answer.
#include <gtest/gtest.h>

#include "registry.hpp"
#include "support/schur_helpers.hpp"

namespace stiction {
namespace {

TEST(FieldsplitSchur, SetUpBuildsTheSplitsSolversAndReportsTheAmgComplexity) {
  const test::StepSystem step("hertz-cylinder-2d");  // displacement and contact multipliers
  auto solver = solvers::create_solver("fieldsplit-schur", PETSC_COMM_WORLD);
  solver->setup(step.system());
  PetscVec x;
  STICTION_PETSC(VecDuplicate(step.system().rhs, x.out()));
  const nonlinear::LinearSolveStats s = solver->solve(step.system(), x);
  EXPECT_TRUE(s.converged) << s.reason;
  ASSERT_TRUE(s.extra.count("amg_operator_complexity")) << "the displacement AMG was not set up by setup()";
  // An aggregation AMG's hierarchy holds more than the fine matrix and, on a 2D
  // elasticity block, well under three times it.
  EXPECT_GT(s.extra.at("amg_operator_complexity"), 1.0);
  EXPECT_LT(s.extra.at("amg_operator_complexity"), 3.0);
}

}  // namespace
}  // namespace stiction
