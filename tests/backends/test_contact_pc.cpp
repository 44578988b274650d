// The global contact level (33): with the exact inverse of the displacement block inside
// and the exact Schur complement S_g = D - B2 A^-1 B1, the four-factor form is the exact
// inverse of the contact system (30): GMRES converges in one iteration.
#include <gtest/gtest.h>

#include <cmath>

#include "contact_pc.hpp"
#include "support/schur_helpers.hpp"

namespace stiction::test {
namespace {

TEST(ContactPreconditioner, ExactSubSolvesGiveTheExactInverse) {
  StepSystem step("hertz-cylinder-2d");
  const auto& sys = step.system();
  const auto* lambda = sys.field("lambda");
  ASSERT_NE(lambda, nullptr);
  ExactHierarchical exact(sys, "test_cpc_hp_");
  set_options("test_cpc_", {{"ss_ksp_type", "preonly"}, {"ss_pc_type", "lu"}});
  solvers::ContactPreconditioner cp(PETSC_COMM_WORLD, "test_cpc_");
  cp.setup(sys.matrix, lambda->is, sys.multiplier_schur_mass, exact.hp);
  // The automatic scale is the geometric mean of the element-end and body-end compliances,
  // and the body's smooth modes are far more compliant than one surface element.
  const auto estimates = cp.scale_estimates();
  EXPECT_GT(estimates.diagonal, 0);
  EXPECT_GT(estimates.smooth, 10 * estimates.diagonal);
  EXPECT_NEAR(cp.scale(), std::sqrt(estimates.diagonal * estimates.smooth), 1e-12 * cp.scale());

  // Approximate S~ (32) first: a working preconditioner, but not exact.
  double residual = 0;
  const int approximate = gmres_iterations(sys, cp, &residual);
  EXPECT_LT(residual, 1e-9);

  PetscInt first;
  ISGetMinMax(lambda->is, &first, nullptr);
  IS is_a;
  ISCreateStride(PETSC_COMM_WORLD, first, 0, 1, &is_a);
  Mat A;
  MatCreateSubMatrix(sys.matrix, is_a, is_a, MAT_INITIAL_MATRIX, &A);
  Mat S = dense_schur_complement(A, cp.block(0, 1), cp.block(1, 0), cp.block(1, 1));
  cp.set_schur_operator(S);
  const int iterations = gmres_iterations(sys, cp, &residual);
  EXPECT_EQ(iterations, 1);
  EXPECT_LT(residual, 1e-9);
  EXPECT_GT(approximate, iterations);
  std::printf("contact level: %d GMRES iterations with S~ (32), %d with the exact S_g\n", approximate, iterations);
  MatDestroy(&S);
  MatDestroy(&A);
  ISDestroy(&is_a);
}

}  // namespace
}  // namespace stiction::test
