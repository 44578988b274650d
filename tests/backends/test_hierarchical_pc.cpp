// HP (10) proven as a factorisation: with exact sub-solves (LU of A_ll, the exact Schur
// complement S = A_qq - A_ql A_ll^-1 A_lq in place of SSOR) the full four-factor form (8)
// is the exact inverse, so GMRES converges in one iteration; the block lower-triangular
// form with exact blocks needs at most two (its preconditioned operator has minimal
// polynomial of degree 2).
#include <gtest/gtest.h>

#include "builtin_scenes.hpp"
#include "common/error.hpp"
#include "hierarchical_pc.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"
#include "support/schur_helpers.hpp"

namespace stiction::solvers {
namespace {

int iterations_with_exact_blocks(SchurForm form, double* residual) {
  test::StepSystem s("cantilever-2d");
  test::ExactHierarchical exact(s.system(), "hp_test_");
  exact.hp.set_form(form);
  return test::gmres_iterations(s.system(), exact.hp, residual);
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

// -<prefix>hp_fact picks the form at set-up (over set_form): with exact blocks, lower needs
// two iterations and full one; another value is an error.
TEST(HierarchicalPreconditioner, HpFactOptionPicksTheForm) {
  test::StepSystem s("cantilever-2d");
  const auto& sys = s.system();
  test::ExactHierarchical exact(sys, "hp_fact_test_");
  auto iterations_with = [&](const char* fact) {
    test::set_options("hp_fact_test_", {{"hp_fact", fact}});
    exact.hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space,
                   sys.field("u_l")->block_size);
    exact.hp.set_quadratic_operator(exact.schur);
    double residual;
    const int its = test::gmres_iterations(sys, exact.hp, &residual);
    EXPECT_LT(residual, 1e-10) << fact;
    return its;
  };
  EXPECT_EQ(iterations_with("lower"), 2);
  EXPECT_EQ(exact.hp.form(), SchurForm::Lower);
  EXPECT_EQ(iterations_with("full"), 1);
  EXPECT_EQ(exact.hp.form(), SchurForm::Full);
  test::set_options("hp_fact_test_", {{"hp_fact", "upper"}});
  EXPECT_THROW(exact.hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space,
                              sys.field("u_l")->block_size),
               Error);
  PetscOptionsClearValue(nullptr, "-hp_fact_test_hp_fact");
}

TEST(HierarchicalPreconditioner, PaperSettingsConvergeInAFewDozenIterations) {
  test::StepSystem s("cantilever-2d");
  const auto& sys = s.system();
  test::set_options("hp_paper_", {{"ll_ksp_type", "preonly"}, {"ll_pc_type", "lu"}, {"qq_ksp_type", "preonly"},
                                  {"qq_pc_type", "sor"}, {"qq_pc_sor_symmetric", nullptr}});
  HierarchicalPreconditioner hp(PETSC_COMM_WORLD, "hp_paper_");
  hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space, sys.field("u_l")->block_size);
  double residual;
  const int its = test::gmres_iterations(sys, hp, &residual);
  EXPECT_LT(residual, 1e-10);
  // Range, not an exact count: SSOR on A_qq is only an approximation of S.
  EXPECT_GT(its, 2);
  EXPECT_LT(its, 50);
}

}  // namespace
}  // namespace stiction::solvers
