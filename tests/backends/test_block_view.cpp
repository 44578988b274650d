// Block views (solvers/block_view.hpp) against copies of the same blocks: products and SOR
// sweeps agree to round-off on a 3D contact system (rows of three with shared columns,
// multiplier columns to skip) and a 2D one; HP holds views by default and copies on request.
#include <gtest/gtest.h>

#include <vector>

#include "support/block_view_checks.hpp"
#include "support/schur_helpers.hpp"

namespace stiction::solvers {
namespace {

// Each flag combination PCSOR can ask for, from a zero and a given guess.
const std::vector<test::SorCase> kSweeps = {{SOR_SYMMETRIC_SWEEP | SOR_ZERO_INITIAL_GUESS, 1.0, 0.0, 1, 1},
                                            {SOR_SYMMETRIC_SWEEP, 1.3, 0.0, 2, 1},
                                            {SOR_FORWARD_SWEEP | SOR_ZERO_INITIAL_GUESS, 0.8, 0.5, 1, 2},
                                            {SOR_BACKWARD_SWEEP | SOR_ZERO_INITIAL_GUESS, 1.0, 0.0, 2, 1},
                                            {SOR_LOCAL_SYMMETRIC_SWEEP, 1.1, 0.0, 1, 1}};

void expect_views_match_copies(const char* scene) {
  test::StepSystem s(scene);
  const test::ViewAgreement a = test::compare_views_with_copies(s.system(), kSweeps);
  EXPECT_TRUE(a.views_are_shells) << scene;
  EXPECT_LT(a.product, 1e-13) << scene;
  EXPECT_LT(a.sweep, 1e-12) << scene;
  EXPECT_EQ(a.diagonal, 0.0) << scene;
}

TEST(BlockView, ProductsAndSweepsMatchCopiesOnA3DContactSystem) { expect_views_match_copies("hertz-sphere-3d"); }

TEST(BlockView, ProductsAndSweepsMatchCopiesOnA2DSystem) { expect_views_match_copies("cantilever-2d"); }

// HP reads A_qq and A_ql in place unless -<prefix>block_copies asks for copies.
TEST(BlockView, HierarchicalPreconditionerHoldsViewsUnlessCopiesAreRequested) {
  test::StepSystem s("cantilever-2d");
  const auto& sys = s.system();
  for (const bool copies : {false, true}) {
    const test::HierarchicalRun run =
        test::run_hierarchical(sys, copies ? "hp_copies_" : "hp_views_", copies, "petsc", "symmetric");
    EXPECT_EQ(run.qq_view, !copies);
    EXPECT_EQ(run.ql_view, !copies);
    EXPECT_FALSE(run.ll_view);  // A_ll: AMG and LU need its entries
    EXPECT_LT(run.residual, 1e-10);
    EXPECT_LT(run.iterations, 50);
  }
}

}  // namespace
}  // namespace stiction::solvers
