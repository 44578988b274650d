// The Krylov diagnostics of every GMRES backend (solvers/ksp_solver.hpp): the stagnation
// test (a hopeless solve stops after one window as DIVERGED_STAGNATION, a slow but steady
// one is left alone), continuing a stagnated solve with a longer restart, and the
// conditioning estimate from GMRES's Hessenberg matrix, and the memory of the Krylov space.
#include <gtest/gtest.h>

#include <petscksp.h>

#include <cmath>
#include <string>

#include "common/petsc.hpp"
#include "nonlinear/newton_system.hpp"
#include "registry.hpp"

namespace {

using stiction::nonlinear::LinearSolveStats;
using stiction::nonlinear::NewtonSystem;

// A system of size n with the given entries (i, j, value) and right side e_0 (or all ones).
NewtonSystem system_of(PetscInt n, const std::vector<std::tuple<PetscInt, PetscInt, double>>& entries,
                       bool ones = false) {
  NewtonSystem s;
  STICTION_PETSC(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 3, nullptr, s.matrix.out()));
  for (const auto& [i, j, v] : entries) STICTION_PETSC(MatSetValue(s.matrix, i, j, v, INSERT_VALUES));
  STICTION_PETSC(MatAssemblyBegin(s.matrix, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(s.matrix, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatCreateVecs(s.matrix, nullptr, s.rhs.out()));
  if (ones) {
    STICTION_PETSC(VecSet(s.rhs, 1.0));
  } else {
    STICTION_PETSC(VecSetValue(s.rhs, 0, 1.0, INSERT_VALUES));
    STICTION_PETSC(VecAssemblyBegin(s.rhs));
    STICTION_PETSC(VecAssemblyEnd(s.rhs));
  }
  return s;
}

// ilu-gmres with the preconditioner switched off and extra options, on `system`.
LinearSolveStats solve_unpreconditioned(const NewtonSystem& system, const std::string& options) {
  STICTION_PETSC(PetscOptionsInsertString(nullptr, ("-ilu_gmres_pc_type none " + options).c_str()));
  auto solver = stiction::solvers::create_solver("ilu-gmres", PETSC_COMM_WORLD);
  solver->setup(system);
  stiction::PetscVec x;
  STICTION_PETSC(VecDuplicate(system.rhs, x.out()));
  const LinearSolveStats stats = solver->solve(system, x);
  STICTION_PETSC(PetscOptionsClearValue(nullptr, "-ilu_gmres_pc_type"));
  STICTION_PETSC(PetscOptionsClearValue(nullptr, "-ilu_gmres_ksp_stagnation_margin"));
  STICTION_PETSC(PetscOptionsClearValue(nullptr, "-ilu_gmres_ksp_gmres_restart"));
  STICTION_PETSC(PetscOptionsClearValue(nullptr, "-ilu_gmres_ksp_rtol"));
  return stats;
}

// The cyclic shift: GMRES on (S, e_0) makes no progress before its n-th iteration, so
// GMRES(100) on n = 300 never converges.
NewtonSystem cyclic_shift(PetscInt n) {
  std::vector<std::tuple<PetscInt, PetscInt, double>> entries;
  for (PetscInt i = 0; i < n; ++i) entries.emplace_back((i + 1) % n, i, 1.0);
  return system_of(n, entries);
}

TEST(KrylovStagnation, AHopelessSolveStopsAfterOneWindow) {
  const NewtonSystem shift = cyclic_shift(300);
  const LinearSolveStats guarded = solve_unpreconditioned(shift, "");
  EXPECT_FALSE(guarded.converged);
  EXPECT_EQ(guarded.reason, "DIVERGED_STAGNATION");
  EXPECT_EQ(guarded.iterations, 500) << "one window of the default 500 iterations";
  // Switched off, the same solve runs to -ksp_max_it (2000 in ilu-gmres.opts).
  const LinearSolveStats unguarded = solve_unpreconditioned(shift, "-ilu_gmres_ksp_stagnation_margin 0");
  EXPECT_FALSE(unguarded.converged);
  EXPECT_EQ(unguarded.reason, "DIVERGED_ITS");
  EXPECT_EQ(unguarded.iterations, 2000);
}

TEST(KrylovStagnation, ASlowSteadySolveIsLeftAlone) {
  // Diagonal, eigenvalues spread evenly over [1, 1000], unpreconditioned GMRES(5): restarted
  // GMRES on a definite matrix gains a steady factor per cycle (588 iterations here).
  const PetscInt n = 1000;
  std::vector<std::tuple<PetscInt, PetscInt, double>> entries;
  for (PetscInt i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0 + 999.0 * i / (n - 1));
  const NewtonSystem diagonal = system_of(n, entries, true);
  const LinearSolveStats guarded = solve_unpreconditioned(diagonal, "-ilu_gmres_ksp_gmres_restart 5");
  const LinearSolveStats unguarded =
      solve_unpreconditioned(diagonal, "-ilu_gmres_ksp_gmres_restart 5 -ilu_gmres_ksp_stagnation_margin 0");
  ASSERT_TRUE(unguarded.converged) << unguarded.reason;
  EXPECT_GT(unguarded.iterations, 500) << "longer than one window, or the test shows nothing";
  EXPECT_TRUE(guarded.converged) << guarded.reason;
  EXPECT_EQ(guarded.iterations, unguarded.iterations);
}

// ilu-gmres, unpreconditioned, on the cyclic shift of size n: solve (stagnates after a
// window), then continue_longer under the given options; true when it continued.
bool stagnate_then_continue(PetscInt n, const std::string& options, LinearSolveStats& stats) {
  const NewtonSystem shift = cyclic_shift(n);
  STICTION_PETSC(PetscOptionsInsertString(nullptr, ("-ilu_gmres_pc_type none " + options).c_str()));
  auto solver = stiction::solvers::create_solver("ilu-gmres", PETSC_COMM_WORLD);
  solver->setup(shift);
  stiction::PetscVec x;
  STICTION_PETSC(VecDuplicate(shift.rhs, x.out()));
  stats = solver->solve(shift, x);
  EXPECT_EQ(stats.reason, "DIVERGED_STAGNATION") << "the first solve must stagnate, or the test shows nothing";
  const bool continued = solver->continue_longer(shift, x, stats);
  for (const char* key : {"-ilu_gmres_pc_type", "-ilu_gmres_ksp_stagnation_restart_factor", "-ilu_gmres_ksp_stagnation_restart_mb"})
    STICTION_PETSC(PetscOptionsClearValue(nullptr, key));
  return continued;
}

TEST(KrylovStagnation, AStagnatedSolveIsContinuedWithALongerRestart) {
  // GMRES(100) makes no progress on the shift of size 250; GMRES(300) (the default factor
  // 3) solves it in exactly 250 iterations from the stagnated iterate (zero).
  LinearSolveStats s;
  ASSERT_TRUE(stagnate_then_continue(250, "", s));
  EXPECT_TRUE(s.converged) << s.reason;
  EXPECT_EQ(s.extra.at("krylov_continued_restart"), 300);
  EXPECT_EQ(s.extra.at("krylov_iterations_before_continuing"), 500);
  EXPECT_EQ(s.iterations, 500 + 250);
  EXPECT_EQ(s.initial_residual, 1.0) << "||b||, not the residual the continued solve started from";
  EXPECT_LE(s.final_residual, s.extra.at("ksp_rtol") * s.initial_residual);
}

TEST(KrylovStagnation, ContinuingIsHeldToItsMemoryBudgetAndCanBeSwitchedOff) {
  LinearSolveStats off;
  EXPECT_FALSE(stagnate_then_continue(250, "-ilu_gmres_ksp_stagnation_restart_factor 1", off));
  EXPECT_EQ(off.reason, "DIVERGED_STAGNATION");
  EXPECT_EQ(off.iterations, 500) << "untouched";
  // 0.3 MB for vectors of 250 doubles: 157 vectors, less 1 + 3 of GMRES's own: GMRES(153),
  // too short for the shift, which stagnates again.
  LinearSolveStats held;
  ASSERT_TRUE(stagnate_then_continue(250, "-ilu_gmres_ksp_stagnation_restart_mb 0.3", held));
  EXPECT_EQ(held.extra.at("krylov_continued_restart"), 153);
  EXPECT_FALSE(held.converged);
  EXPECT_EQ(held.reason, "DIVERGED_STAGNATION");
  // No room for a basis longer than the first one: nothing to try.
  LinearSolveStats none;
  EXPECT_FALSE(stagnate_then_continue(250, "-ilu_gmres_ksp_stagnation_restart_mb 0.1", none));
}

// The 1D Laplacian tridiag(-1, 2, -1) of size n, symmetric positive definite, has the
// singular values 2 - 2 cos(k pi / (n + 1)), k = 1..n, with eigenvectors sin(k j pi / (n + 1)).
// The right side e_0 has a component along every one of them (a constant right side misses
// the even k, the largest among them), so unpreconditioned GMRES without a restart spans the
// whole space before it converges to 1e-12 and its Hessenberg matrix holds the extreme
// singular values: the estimate must match the exact condition number.
TEST(KrylovConditioning, GmresEstimatesTheConditionOfTheLaplacian) {
  const PetscInt n = 40;
  std::vector<std::tuple<PetscInt, PetscInt, double>> entries;
  for (PetscInt i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.0);
  }
  const NewtonSystem laplacian = system_of(n, entries);
  const LinearSolveStats s = solve_unpreconditioned(laplacian, "-ilu_gmres_ksp_gmres_restart 100 -ilu_gmres_ksp_rtol 1e-12");
  ASSERT_TRUE(s.converged) << s.reason;
  const double pi = std::acos(-1.0);
  const double sigma_max = 2 - 2 * std::cos(n * pi / (n + 1)), sigma_min = 2 - 2 * std::cos(pi / (n + 1));
  ASSERT_TRUE(s.extra.count("condition_estimate")) << "no conditioning estimate reported";
  EXPECT_NEAR(s.extra.at("sigma_max_estimate"), sigma_max, 1e-6 * sigma_max);
  EXPECT_NEAR(s.extra.at("sigma_min_estimate"), sigma_min, 1e-6 * sigma_min);
  EXPECT_NEAR(s.extra.at("condition_estimate"), sigma_max / sigma_min, 1e-6 * sigma_max / sigma_min);
}

// The Krylov space a KSP holds is reported with every solve (memory_krylov_MB), also by
// the solves that reuse it (a system without contact keeps its KSP), until release()
// frees it with the set-up.
TEST(KrylovMemory, TheKrylovSpaceHeldIsReportedAtEverySolveUntilReleased) {
  const PetscInt n = 20000;  // 156 KB per vector
  std::vector<std::tuple<PetscInt, PetscInt, double>> entries;
  for (PetscInt i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.0);
  }
  const NewtonSystem laplacian = system_of(n, entries, true);
  // 30 unpreconditioned iterations never reach 1e-12 here: each solve fills the basis of 30.
  STICTION_PETSC(PetscOptionsInsertString(
      nullptr, "-ilu_gmres_pc_type none -ilu_gmres_ksp_gmres_restart 30 -ilu_gmres_ksp_max_it 30 -ilu_gmres_ksp_rtol 1e-12"));
  auto solver = stiction::solvers::create_solver("ilu-gmres", PETSC_COMM_WORLD);
  stiction::PetscVec x;
  STICTION_PETSC(VecDuplicate(laplacian.rhs, x.out()));
  auto krylov_mb = [&] {
    STICTION_PETSC(VecZeroEntries(x));
    const LinearSolveStats s = solver->solve(laplacian, x);
    EXPECT_EQ(s.iterations, 30);
    // The resident figures beside it: now, at the peak so far, and the freed heap held.
    EXPECT_GT(s.extra.at("memory_resident_MB"), 0);
    EXPECT_GE(s.extra.at("memory_peak_resident_MB"), s.extra.at("memory_resident_MB"));
    EXPECT_GE(s.extra.at("memory_heap_free_MB"), 0);
    return s.extra.at("memory_krylov_MB");
  };
  solver->setup(laplacian);
  const double first = krylov_mb(), again = krylov_mb();
  solver->release();
  solver->setup(laplacian);
  const double after_release = krylov_mb();
  for (const char* key : {"-ilu_gmres_pc_type", "-ilu_gmres_ksp_gmres_restart", "-ilu_gmres_ksp_max_it", "-ilu_gmres_ksp_rtol"})
    STICTION_PETSC(PetscOptionsClearValue(nullptr, key));
  const double basis_mb = 30.0 * n * sizeof(PetscScalar) / 1048576.0;
  // GMRES allocates its first few vectors at set-up, the rest as the basis grows.
  EXPECT_GT(first, 0.8 * basis_mb);
  EXPECT_LT(first, 1.2 * basis_mb);
  EXPECT_NEAR(again, first, 0.05 * first) << "the second solve reuses the basis of the first";
  EXPECT_NEAR(after_release, first, 0.05 * first) << "released, the basis is allocated (and counted) afresh";
}

}  // namespace
