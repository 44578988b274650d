// Per-backend micro-benchmarks on the first Newton system of block-compression at level 0
// (45k unknowns): set-up (factorisation / preconditioner construction) and one
// preconditioner application (for direct backends: one pair of triangular solves).
//
//   build/benchmarks/bench_backends [--benchmark_filter=schur]
// The KSP view and Krylov counts of each backend are in the sweep reports; this measures
// only the two costs a Krylov method multiplies.
#include <benchmark/benchmark.h>
// PetscObjectStateIncrease is only in the private header; the benchmark needs it to force
// a real set-up each iteration.
#include <petsc/private/petscimpl.h>

#include <memory>

#include "builtin_scenes.hpp"
#include "common/petsc.hpp"
#include "common/process_memory.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"

namespace {

using namespace stiction;

// The Newton system of step 1, iteration 1, assembled once by the real driver.
struct Level0System {
  std::unique_ptr<scene::Scene> scene = harness::open_scene("block-compression", 0);
  std::unique_ptr<nonlinear::LinearSolver> lu = solvers::create_solver("lu-mumps", PETSC_COMM_WORLD);
  std::unique_ptr<nonlinear::QuasiStaticSolver> newton;
  Level0System() {
    scene->newton.max_iterations = 1;  // stop after assembling and solving the first system
    newton = std::make_unique<nonlinear::QuasiStaticSolver>(PETSC_COMM_WORLD, scene->problem, scene->newton, *lu);
    newton->solve_step(1);
  }
};

// Owned here and released before PETSc finalises (a static would be destroyed after).
std::unique_ptr<Level0System> g_level0;

const nonlinear::NewtonSystem& level0() {
  if (!g_level0) g_level0 = std::make_unique<Level0System>();
  return g_level0->newton->system();
}

void BM_Setup(benchmark::State& state, const std::string& backend) {
  const auto& sys = level0();
  auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);
  for (auto _ : state) {
    // Mark the matrix as changed, as a Newton iteration does: PETSc skips an unchanged set-up.
    PetscObjectStateIncrease(reinterpret_cast<PetscObject>(sys.matrix.get()));
    solver->setup(sys);
  }
  PetscInt n;
  MatGetSize(sys.matrix, &n, nullptr);
  state.counters["unknowns"] = static_cast<double>(n);
  state.counters["MDof/s"] = benchmark::Counter(n * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}

// One application of the preconditioner (PCApply; for direct backends the triangular solves).
void BM_ApplyPreconditioner(benchmark::State& state, const std::string& backend) {
  const auto& sys = level0();
  auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);
  solver->setup(sys);
  PetscVec z;
  VecDuplicate(sys.rhs, z.out());
  for (auto _ : state) solver->apply_preconditioner(sys.rhs, z);
  PetscInt n;
  MatGetSize(sys.matrix, &n, nullptr);
  state.counters["unknowns"] = static_cast<double>(n);
  state.counters["MDof/s"] = benchmark::Counter(n * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}

void register_all() {
  for (const auto& b : solvers::backends()) {
    if (!b.unavailable_reason().empty()) continue;
    benchmark::RegisterBenchmark(("Setup/" + b.name).c_str(), BM_Setup, b.name)->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark(("ApplyOnce/" + b.name).c_str(), BM_ApplyPreconditioner, b.name)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
  restart_with_huge_pages_for_mapped_blocks(argv);  // as stiction does: the same allocator
  benchmark::Initialize(&argc, argv);
  int pargc = 1;
  PetscSession petsc(&pargc, &argv);
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  g_level0.reset();
  return 0;
}
