// HP (10) proven as a factorisation: with exact sub-solves (LU of A_ll, the exact Schur
// complement S = A_qq - A_ql A_ll^-1 A_lq in place of SSOR) the full four-factor form (8)
// is the exact inverse, so GMRES converges in one iteration; the block lower-triangular
// form with exact blocks needs at most two (its preconditioned operator has minimal
// polynomial of degree 2).
#include <gtest/gtest.h>

#include "builtin_scenes.hpp"
#include "hierarchical_pc.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"

namespace stiction::solvers {
namespace {

// The Newton system of the first iteration of cantilever-2d (level 0), assembled by the
// real driver.
struct SmallSystem {
  std::unique_ptr<scene::Scene> scene = harness::open_scene("cantilever-2d", 0);
  std::unique_ptr<nonlinear::LinearSolver> lu = create_solver("lu-mumps", PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton{PETSC_COMM_WORLD, scene->problem, scene->newton, *lu};
  SmallSystem() { newton.solve_step(1); }
  const nonlinear::NewtonSystem& system() const { return newton.system(); }
};

// Dense S = A_qq - A_ql A_ll^-1 A_lq.
Mat exact_schur(HierarchicalPreconditioner& hp) {
  Mat All = hp.block(0, 0), Alq = hp.block(0, 1), Aql = hp.block(1, 0), Aqq = hp.block(1, 1);
  Mat F, B, X, S, AqlX;
  MatFactorInfo info;
  MatFactorInfoInitialize(&info);
  IS rperm, cperm;
  MatGetOrdering(All, MATORDERINGND, &rperm, &cperm);
  MatGetFactor(All, MATSOLVERPETSC, MAT_FACTOR_LU, &F);
  MatLUFactorSymbolic(F, All, rperm, cperm, &info);
  MatLUFactorNumeric(F, All, &info);
  MatConvert(Alq, MATSEQDENSE, MAT_INITIAL_MATRIX, &B);
  MatDuplicate(B, MAT_DO_NOT_COPY_VALUES, &X);
  MatMatSolve(F, B, X);
  MatMatMult(Aql, X, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &AqlX);
  MatConvert(Aqq, MATSEQDENSE, MAT_INITIAL_MATRIX, &S);
  MatAXPY(S, -1.0, AqlX, SAME_NONZERO_PATTERN);
  for (Mat* m : {&F, &B, &X, &AqlX}) MatDestroy(m);
  ISDestroy(&rperm);
  ISDestroy(&cperm);
  return S;
}

int gmres_iterations(const nonlinear::NewtonSystem& sys, HierarchicalPreconditioner& hp, double* residual) {
  KSP ksp;
  PC pc;
  Vec x, r;
  KSPCreate(PETSC_COMM_WORLD, &ksp);
  KSPSetOperators(ksp, sys.matrix, sys.matrix);
  KSPSetType(ksp, KSPGMRES);
  KSPSetPCSide(ksp, PC_RIGHT);
  KSPSetTolerances(ksp, 1e-10, 1e-50, 1e10, 50);
  KSPGetPC(ksp, &pc);
  use_as_shell(pc, hp, "HP under test");
  MatCreateVecs(sys.matrix, &x, &r);
  KSPSolve(ksp, sys.rhs, x);
  PetscInt its;
  KSPGetIterationNumber(ksp, &its);
  PetscReal bnorm, rnorm;
  MatMult(sys.matrix, x, r);
  VecAYPX(r, -1.0, sys.rhs);
  VecNorm(r, NORM_2, &rnorm);
  VecNorm(sys.rhs, NORM_2, &bnorm);
  *residual = rnorm / bnorm;
  VecDestroy(&x);
  VecDestroy(&r);
  KSPDestroy(&ksp);
  return static_cast<int>(its);
}

int iterations_with_exact_blocks(SchurForm form, double* residual) {
  SmallSystem s;
  const auto& sys = s.system();
  PetscOptionsSetValue(nullptr, "-hp_test_ll_ksp_type", "preonly");
  PetscOptionsSetValue(nullptr, "-hp_test_ll_pc_type", "lu");
  PetscOptionsSetValue(nullptr, "-hp_test_qq_ksp_type", "preonly");
  PetscOptionsSetValue(nullptr, "-hp_test_qq_pc_type", "lu");
  HierarchicalPreconditioner hp(PETSC_COMM_WORLD, "hp_test_");
  hp.set_form(SchurForm::Full);  // extracts A_lq, needed for S
  hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space, sys.field("u_l")->block_size);
  hp.set_form(form);
  Mat S = exact_schur(hp);
  hp.set_quadratic_operator(S);
  const int its = gmres_iterations(sys, hp, residual);
  MatDestroy(&S);
  return its;
}

TEST(HierarchicalPreconditioner, FullFormWithExactBlocksIsTheInverse) {
  double residual;
  EXPECT_EQ(iterations_with_exact_blocks(SchurForm::Full, &residual), 1);
  EXPECT_LT(residual, 1e-10);
}

TEST(HierarchicalPreconditioner, LowerFormWithExactBlocksNeedsTwoIterations) {
  double residual;
  EXPECT_LE(iterations_with_exact_blocks(SchurForm::Lower, &residual), 2);
  EXPECT_LT(residual, 1e-10);
}

TEST(HierarchicalPreconditioner, PaperSettingsConvergeInAFewDozenIterations) {
  SmallSystem s;
  const auto& sys = s.system();
  PetscOptionsSetValue(nullptr, "-hp_paper_ll_ksp_type", "preonly");
  PetscOptionsSetValue(nullptr, "-hp_paper_ll_pc_type", "lu");
  PetscOptionsSetValue(nullptr, "-hp_paper_qq_ksp_type", "preonly");
  PetscOptionsSetValue(nullptr, "-hp_paper_qq_pc_type", "sor");
  PetscOptionsSetValue(nullptr, "-hp_paper_qq_pc_sor_symmetric", nullptr);
  HierarchicalPreconditioner hp(PETSC_COMM_WORLD, "hp_paper_");
  hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space, sys.field("u_l")->block_size);
  double residual;
  const int its = gmres_iterations(sys, hp, &residual);
  EXPECT_LT(residual, 1e-10);
  // Range, not an exact count: SSOR on A_qq is only an approximation of S.
  EXPECT_GT(its, 2);
  EXPECT_LT(its, 50);
}

}  // namespace
}  // namespace stiction::solvers
