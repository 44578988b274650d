// The contact level's direct solve (pivoting_fallback.hpp): a nonsingular matrix whose every
// symmetric ordering starts a pivot-free LU on a zero diagonal entry is factored by MUMPS
// after PETSc's own LU fails, and the solve is exact.
#include <gtest/gtest.h>

#include <cmath>

#include "common/petsc.hpp"
#include "pivoting_fallback.hpp"

namespace stiction::test {
namespace {

// [[0 1 0] [1 0 0] [0 0 4]]: the 2x2 block has zero diagonals in either order.
PetscMat zero_diagonal_matrix() {
  PetscMat A;
  STICTION_PETSC(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 2, nullptr, A.out()));
  STICTION_PETSC(MatSetValue(A, 0, 1, 1.0, INSERT_VALUES));
  STICTION_PETSC(MatSetValue(A, 1, 0, 1.0, INSERT_VALUES));
  STICTION_PETSC(MatSetValue(A, 2, 2, 4.0, INSERT_VALUES));
  for (PetscInt i = 0; i < 2; ++i) STICTION_PETSC(MatSetValue(A, i, i, 0.0, INSERT_VALUES));
  STICTION_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  return A;
}

PetscKSP direct_solver(Mat A) {
  PetscKSP ksp;
  STICTION_PETSC(KSPCreate(PETSC_COMM_SELF, ksp.out()));
  STICTION_PETSC(KSPSetType(ksp, KSPPREONLY));
  PC pc;
  STICTION_PETSC(KSPGetPC(ksp, &pc));
  STICTION_PETSC(PCSetType(pc, PCLU));
  STICTION_PETSC(PCFactorSetMatOrderingType(pc, MATORDERINGND));
  STICTION_PETSC(KSPSetOperators(ksp, A, A));
  return ksp;
}

// Solves A x = A (1, 2, 3) and returns the largest error of x.
double solve_error(KSP ksp, Mat A) {
  PetscVec x, b, exact;
  STICTION_PETSC(MatCreateVecs(A, x.out(), b.out()));
  STICTION_PETSC(VecDuplicate(x, exact.out()));
  for (PetscInt i = 0; i < 3; ++i) STICTION_PETSC(VecSetValue(exact, i, i + 1.0, INSERT_VALUES));
  STICTION_PETSC(VecAssemblyBegin(exact));
  STICTION_PETSC(VecAssemblyEnd(exact));
  STICTION_PETSC(MatMult(A, exact, b));
  STICTION_PETSC(KSPSolve(ksp, b, x));
  STICTION_PETSC(VecAXPY(x, -1.0, exact));
  PetscReal error;
  STICTION_PETSC(VecNorm(x, NORM_INFINITY, &error));
  return error;
}

}  // namespace

TEST(PivotingFallback, PetscLuFailsOnTheZeroDiagonalAndMumpsSolvesIt) {
  PetscMat A = zero_diagonal_matrix();
  {  // the condition the fallback is for: PETSc's LU alone stops on a zero pivot
    PetscKSP plain = direct_solver(A);
    STICTION_PETSC(KSPSetUp(plain));
    PC pc;
    STICTION_PETSC(KSPGetPC(plain, &pc));
    PCFailedReason reason;
    STICTION_PETSC(PCGetFailedReason(pc, &reason));
    ASSERT_NE(reason, PC_NOERROR);
    EXPECT_FALSE(std::isfinite(solve_error(plain, A)));
  }
  PetscKSP ksp = direct_solver(A);
  EXPECT_TRUE(solvers::set_up_with_pivoting_fallback(ksp));
  EXPECT_TRUE(solvers::factored_by_mumps(ksp));
  EXPECT_LT(solve_error(ksp, A), 1e-14);
  // Later set-ups keep MUMPS without a failed attempt first.
  STICTION_PETSC(KSPSetOperators(ksp, A, A));
  EXPECT_FALSE(solvers::set_up_with_pivoting_fallback(ksp));
  EXPECT_TRUE(solvers::factored_by_mumps(ksp));
  EXPECT_LT(solve_error(ksp, A), 1e-14);
}

TEST(PivotingFallback, KeepsPetscLuWhenItFactors) {
  PetscMat A;
  STICTION_PETSC(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 1, nullptr, A.out()));
  for (PetscInt i = 0; i < 3; ++i) STICTION_PETSC(MatSetValue(A, i, i, 2.0 + i, INSERT_VALUES));
  STICTION_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscKSP ksp = direct_solver(A);
  EXPECT_FALSE(solvers::set_up_with_pivoting_fallback(ksp));
  EXPECT_FALSE(solvers::factored_by_mumps(ksp));
  EXPECT_LT(solve_error(ksp, A), 1e-15);
}

}  // namespace stiction::test
