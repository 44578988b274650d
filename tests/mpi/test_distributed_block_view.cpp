// Run under `mpirun -n 2` with the other distributed tests. Block views of a distributed
// Newton system (an MPIAIJ matrix: each process's rows in a diagonal and an off-process
// part) against copies of the same blocks: products, process-local SOR sweeps and the
// diagonal agree to round-off, and HP holds views on several processes and converges in
// as many GMRES iterations as with copies.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "support/block_view_checks.hpp"
#include "support/schur_helpers.hpp"  // StepSystem
#include "support/test_names.hpp"

namespace {

using namespace stiction;

void expect_distributed(const nonlinear::NewtonSystem& sys) {
  int processes = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &processes);
  ASSERT_EQ(processes, 2) << "run under mpirun -n 2";
  PetscInt local, global;
  MatGetLocalSize(sys.matrix, &local, nullptr);
  MatGetSize(sys.matrix, &global, nullptr);
  ASSERT_GT(local, 0);
  ASSERT_LT(local, global);
}

// Only process-local sweeps exist on a distributed matrix (MatSOR_MPIAIJ).
const std::vector<test::SorCase> kLocalSweeps = {
    {SOR_LOCAL_SYMMETRIC_SWEEP | SOR_ZERO_INITIAL_GUESS, 1.0, 0.0, 1, 1},
    {SOR_LOCAL_SYMMETRIC_SWEEP, 1.3, 0.0, 2, 1},
    {SOR_LOCAL_FORWARD_SWEEP | SOR_ZERO_INITIAL_GUESS, 0.8, 0.5, 2, 2},
    {SOR_LOCAL_BACKWARD_SWEEP | SOR_ZERO_INITIAL_GUESS, 1.0, 0.0, 3, 1}};

class DistributedBlockView : public ::testing::TestWithParam<const char*> {};

TEST_P(DistributedBlockView, ProductsAndLocalSweepsMatchCopies) {
  test::StepSystem s(GetParam());
  expect_distributed(s.system());
  const test::ViewAgreement a = test::compare_views_with_copies(s.system(), kLocalSweeps);
  EXPECT_TRUE(a.views_are_shells);
  EXPECT_LT(a.product, 1e-13);
  EXPECT_LT(a.sweep, 1e-12);
  EXPECT_EQ(a.diagonal, 0.0);
}

// 3D contact (rows of three, multiplier columns to skip) and 2D.
INSTANTIATE_TEST_SUITE_P(Scenes, DistributedBlockView, ::testing::Values("hertz-sphere-3d", "cantilever-2d"),
                         [](const auto& info) { return test::identifier(info.param); });

TEST(DistributedBlockView, HierarchicalPreconditionerHoldsViewsOnSeveralProcesses) {
  test::StepSystem s("cantilever-2d");
  const auto& sys = s.system();
  expect_distributed(sys);
  test::HierarchicalRun runs[2];
  for (const bool copies : {false, true}) {
    runs[copies] =
        test::run_hierarchical(sys, copies ? "mpi_hp_copies_" : "mpi_hp_views_", copies, "mumps", "local_symmetric");
    EXPECT_EQ(runs[copies].qq_view, !copies);
    EXPECT_EQ(runs[copies].ql_view, !copies);
    EXPECT_LT(runs[copies].residual, 1e-10);
  }
  EXPECT_LT(runs[0].iterations, 60);
  EXPECT_EQ(runs[0].iterations, runs[1].iterations);
}

}  // namespace
