// MHP (11) proven as a factorisation on a mixed (u-p) Mooney-Rivlin system (Cook's
// membrane, plane strain): with exact inner solves (HP in its full form with the exact
// S_q, and the exact pressure Schur complement S_p = C - Bp A^-1 Bp^T) the full form is
// the exact inverse, GMRES converges in one iteration; the paper's block upper-triangular
// form with exact blocks needs at most two. With the paper's settings (LU on A_ll, SSOR on
// A_qq, SSOR on alpha M_p) it converges within a range.
#include <gtest/gtest.h>

#include "builtin_scenes.hpp"
#include "field_sets.hpp"
#include "mixed_pc.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"
#include "support/schur_helpers.hpp"

namespace stiction::solvers {
namespace {

// The form set by set_form, or (by_option) by -<prefix>mhp_fact.
int iterations_with_exact_blocks(SchurForm mixed_form, double* residual, bool by_option = false) {
  test::StepSystem s("cook-membrane-2d");
  const auto& sys = s.system();
  EXPECT_NE(sys.field("p"), nullptr);
  const bool full = mixed_form == SchurForm::Full;
  const std::string prefix = std::string(by_option ? "mhp_option_" : "mhp_") + (full ? "full_" : "upper_");
  test::set_options(prefix, {{"pp_ksp_type", "preonly"}, {"pp_pc_type", "lu"}});
  if (by_option) test::set_options(prefix, {{"mhp_fact", full ? "full" : "upper"}});
  test::ExactHierarchical exact(sys, prefix);  // HP is the exact A^-1

  MixedPreconditioner mhp(PETSC_COMM_WORLD, prefix, exact.hp);
  if (!by_option) mhp.set_form(mixed_form);
  mhp.setup(sys.matrix, union_of_fields(sys, {"u_l", "u_q"}), sys.field("p")->is, sys.pressure_mass,
            sys.mixed_shear_modulus, sys.mixed_bulk_modulus);
  // Exact S_p = C - Bp A^-1 Bp^T with A the whole displacement block.
  IS is_u, is_p = sys.field("p")->is;
  PetscInt first;
  ISGetMinMax(is_p, &first, nullptr);
  ISCreateStride(PETSC_COMM_WORLD, first, 0, 1, &is_u);
  Mat A, C, Bt, B;
  MatCreateSubMatrix(sys.matrix, is_u, is_u, MAT_INITIAL_MATRIX, &A);
  MatCreateSubMatrix(sys.matrix, is_p, is_p, MAT_INITIAL_MATRIX, &C);
  MatCreateSubMatrix(sys.matrix, is_u, is_p, MAT_INITIAL_MATRIX, &Bt);
  MatCreateSubMatrix(sys.matrix, is_p, is_u, MAT_INITIAL_MATRIX, &B);
  Mat Sp = test::dense_schur_complement(A, Bt, B, C);
  mhp.set_pressure_operator(Sp);
  const int its = test::gmres_iterations(sys, mhp, residual);
  for (Mat* m : {&Sp, &A, &C, &Bt, &B}) MatDestroy(m);
  ISDestroy(&is_u);
  return its;
}

TEST(MixedPreconditioner, FullFormWithExactBlocksIsTheInverse) {
  double residual;
  EXPECT_EQ(iterations_with_exact_blocks(SchurForm::Full, &residual), 1);
  EXPECT_LT(residual, 1e-10);
}

TEST(MixedPreconditioner, UpperFormWithExactBlocksNeedsTwoIterations) {
  double residual;
  EXPECT_LE(iterations_with_exact_blocks(SchurForm::Upper, &residual), 2);
  EXPECT_LT(residual, 1e-10);
}

// -<prefix>mhp_fact chooses the form: full gives the exact inverse as set_form does.
TEST(MixedPreconditioner, FormChosenByOption) {
  double residual;
  EXPECT_EQ(iterations_with_exact_blocks(SchurForm::Full, &residual, true), 1);
  EXPECT_LT(residual, 1e-10);
  EXPECT_EQ(iterations_with_exact_blocks(SchurForm::Upper, &residual, true), 2);
}

TEST(MixedPreconditioner, BadFormOptionIsRefusedWithItsName) {
  test::StepSystem s("cook-membrane-2d");
  const auto& sys = s.system();
  test::set_options("mhp_bad_", {{"mhp_fact", "lower"}});
  test::ExactHierarchical exact(sys, "mhp_bad_");
  MixedPreconditioner mhp(PETSC_COMM_WORLD, "mhp_bad_", exact.hp);
  try {
    mhp.setup(sys.matrix, union_of_fields(sys, {"u_l", "u_q"}), sys.field("p")->is, sys.pressure_mass,
              sys.mixed_shear_modulus, sys.mixed_bulk_modulus);
    ADD_FAILURE() << "mhp_fact lower was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("-mhp_bad_mhp_fact"), std::string::npos) << e.what();
  }
}

TEST(MixedPreconditioner, PaperSettingsConverge) {
  test::StepSystem s("cook-membrane-2d");
  const auto& sys = s.system();
  test::set_options("mhp_paper_", {{"ll_ksp_type", "preonly"}, {"ll_pc_type", "lu"}, {"qq_ksp_type", "preonly"},
                                   {"qq_pc_type", "sor"}, {"qq_pc_sor_symmetric", nullptr}, {"pp_ksp_type", "preonly"},
                                   {"pp_pc_type", "sor"}, {"pp_pc_sor_symmetric", nullptr}});
  HierarchicalPreconditioner hp(PETSC_COMM_WORLD, "mhp_paper_");
  hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space, 2);
  MixedPreconditioner mhp(PETSC_COMM_WORLD, "mhp_paper_", hp);
  mhp.setup(sys.matrix, union_of_fields(sys, {"u_l", "u_q"}), sys.field("p")->is, sys.pressure_mass,
            sys.mixed_shear_modulus, sys.mixed_bulk_modulus);
  double residual;
  const int its = test::gmres_iterations(sys, mhp, &residual);
  EXPECT_LT(residual, 1e-10);
  EXPECT_GT(its, 2);    // an approximation, not the inverse
  EXPECT_LT(its, 120);  // range, not an exact count
}

}  // namespace
}  // namespace stiction::solvers
