// Block views (solvers/block_view.hpp) against copies of the same blocks: products and SOR
// sweeps agree to round-off on a 3D contact system (rows of three with shared columns,
// multiplier columns to skip) and a 2D one; HP holds views by default and copies on request.
#include <gtest/gtest.h>

#include <cmath>

#include "block_view.hpp"
#include "hierarchical_pc.hpp"
#include "support/schur_helpers.hpp"

namespace stiction::solvers {
namespace {

double relative_difference(Vec a, Vec b) {
  PetscVec d;
  VecDuplicate(a, d.out());
  VecWAXPY(d, -1.0, a, b);
  PetscReal nd, na;
  VecNorm(d, NORM_2, &nd);
  VecNorm(a, NORM_2, &na);
  return nd / na;
}

struct Blocks {
  IndexRange l, q;
  PetscMat ll_view, qq_view, ql_view, lq_view, qq_copy, ql_copy, lq_copy;
};

Blocks blocks_of(const nonlinear::NewtonSystem& sys) {
  Blocks b;
  IS l = sys.field("u_l")->is, q = sys.field("u_q")->is;
  b.l = contiguous_range(l);
  b.q = contiguous_range(q);
  *b.qq_view.out() = block_view(sys.matrix, b.q, b.q);
  *b.ql_view.out() = block_view(sys.matrix, b.q, b.l);
  *b.lq_view.out() = block_view(sys.matrix, b.l, b.q);
  MatCreateSubMatrix(sys.matrix, q, q, MAT_INITIAL_MATRIX, b.qq_copy.out());
  MatCreateSubMatrix(sys.matrix, q, l, MAT_INITIAL_MATRIX, b.ql_copy.out());
  MatCreateSubMatrix(sys.matrix, l, q, MAT_INITIAL_MATRIX, b.lq_copy.out());
  return b;
}

void expect_views_match_copies(const char* scene) {
  test::StepSystem s(scene);
  const auto& sys = s.system();
  Blocks b = blocks_of(sys);
  ASSERT_GT(b.l.size, 0);
  ASSERT_GT(b.q.size, 0);
  PetscRandom rng;
  PetscRandomCreate(PETSC_COMM_WORLD, &rng);
  // Products of every off-diagonal and diagonal block.
  for (auto [view, copy] : {std::pair{b.qq_view.get(), b.qq_copy.get()}, std::pair{b.ql_view.get(), b.ql_copy.get()},
                            std::pair{b.lq_view.get(), b.lq_copy.get()}}) {
    PetscVec x, y_view, y_copy;
    MatCreateVecs(copy, x.out(), y_copy.out());
    VecDuplicate(y_copy, y_view.out());
    VecSetRandom(x, rng);
    MatMult(copy, x, y_copy);
    MatMult(view, x, y_view);
    EXPECT_LT(relative_difference(y_copy, y_view), 1e-13) << scene;
  }
  // SOR sweeps, each flag combination PCSOR can ask for, from a zero and a given guess.
  struct Case {
    int flag;
    double omega, shift;
    PetscInt its, lits;
  };
  for (const Case c : {Case{SOR_SYMMETRIC_SWEEP | SOR_ZERO_INITIAL_GUESS, 1.0, 0.0, 1, 1},
                       Case{SOR_SYMMETRIC_SWEEP, 1.3, 0.0, 2, 1},
                       Case{SOR_FORWARD_SWEEP | SOR_ZERO_INITIAL_GUESS, 0.8, 0.5, 1, 2},
                       Case{SOR_BACKWARD_SWEEP | SOR_ZERO_INITIAL_GUESS, 1.0, 0.0, 2, 1},
                       Case{SOR_LOCAL_SYMMETRIC_SWEEP, 1.1, 0.0, 1, 1}}) {
    PetscVec rhs, guess, x_view, x_copy;
    MatCreateVecs(b.qq_copy, guess.out(), rhs.out());
    VecSetRandom(rhs, rng);
    VecSetRandom(guess, rng);
    VecDuplicate(guess, x_view.out());
    VecDuplicate(guess, x_copy.out());
    VecCopy(guess, x_view);
    VecCopy(guess, x_copy);
    MatSOR(b.qq_copy, rhs, c.omega, static_cast<MatSORType>(c.flag), c.shift, c.its, c.lits, x_copy);
    ASSERT_EQ(MatSOR(b.qq_view, rhs, c.omega, static_cast<MatSORType>(c.flag), c.shift, c.its, c.lits, x_view), 0);
    EXPECT_LT(relative_difference(x_copy, x_view), 1e-12) << scene << ", SOR flag " << c.flag;
  }
  // The diagonal (PCJACOBI).
  PetscVec d_view, d_copy;
  MatCreateVecs(b.qq_copy, d_copy.out(), nullptr);
  VecDuplicate(d_copy, d_view.out());
  MatGetDiagonal(b.qq_copy, d_copy);
  MatGetDiagonal(b.qq_view, d_view);
  EXPECT_EQ(relative_difference(d_copy, d_view), 0.0);
  PetscRandomDestroy(&rng);
}

TEST(BlockView, ProductsAndSweepsMatchCopiesOnA3DContactSystem) { expect_views_match_copies("hertz-sphere-3d"); }

TEST(BlockView, ProductsAndSweepsMatchCopiesOnA2DSystem) { expect_views_match_copies("cantilever-2d"); }

// HP reads A_qq and A_ql in place unless -<prefix>block_copies asks for copies.
TEST(BlockView, HierarchicalPreconditionerHoldsViewsUnlessCopiesAreRequested) {
  test::StepSystem s("cantilever-2d");
  const auto& sys = s.system();
  for (const bool copies : {false, true}) {
    const std::string prefix = copies ? "hp_copies_" : "hp_views_";
    test::set_options(prefix, {{"ll_ksp_type", "preonly"}, {"ll_pc_type", "lu"}, {"qq_ksp_type", "preonly"},
                               {"qq_pc_type", "sor"}, {"qq_pc_sor_symmetric", nullptr}});
    if (copies) test::set_options(prefix, {{"block_copies", "true"}});
    HierarchicalPreconditioner hp(PETSC_COMM_WORLD, prefix);
    hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space,
             sys.field("u_l")->block_size);
    for (auto [row, col] : {std::pair{1, 1}, std::pair{1, 0}}) {
      PetscBool shell;
      PetscObjectTypeCompare(reinterpret_cast<PetscObject>(hp.block(row, col)), MATSHELL, &shell);
      EXPECT_EQ(static_cast<bool>(shell), !copies) << "block " << row << col;
    }
    PetscBool shell;
    PetscObjectTypeCompare(reinterpret_cast<PetscObject>(hp.block(0, 0)), MATSHELL, &shell);
    EXPECT_FALSE(shell);  // A_ll: AMG and LU need its entries
    double residual;
    const int its = test::gmres_iterations(sys, hp, &residual);
    EXPECT_LT(residual, 1e-10);
    EXPECT_LT(its, 50);
  }
}

}  // namespace
}  // namespace stiction::solvers
