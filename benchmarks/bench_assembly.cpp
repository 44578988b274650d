// Assembly micro-benchmarks on the built-in block-compression scene (P2 hierarchical,
// Neo-Hookean) at mesh levels 0 and 1, at the state after one load step's worth of
// compression so the tangent is a genuine finite-strain one.
//
//   build/benchmarks/bench_assembly [--benchmark_filter=...] [--benchmark_format=json]
//
// Counters: unknowns, MDof/s (unknowns per second of one residual + tangent assembly),
// matrix_MB (AIJ storage: values + column indices + row offsets), peak_RSS_MB (VmHWM of
// the process after assembling: mesh, space, matrix and work vectors).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "builtin_scenes.hpp"
#include "common/petsc.hpp"
#include "common/process_memory.hpp"
#include "fem/elasticity_assembly.hpp"
#include "solver_figures.hpp"

namespace {

using namespace stiction;

// One scene per level, built once (Gmsh + refinement are not what is measured).
scene::Scene& block(int level) {
  static std::map<int, std::unique_ptr<scene::Scene>> scenes;
  auto& s = scenes[level];
  if (!s) s = harness::open_scene("block-compression", level);
  return *s;
}

std::vector<double> compressed_state(const fem::FieldSpace& space) {
  std::vector<double> u;  // 2% homogeneous compression along z: F = diag(1, 1, 0.98)
  space.interpolate([&](const double* X, double* out) { out[0] = 0, out[1] = 0, out[2] = -0.02 * X[2]; }, u);
  return u;
}

void BM_ResidualAndTangent(benchmark::State& state) {
  scene::Scene& s = block(static_cast<int>(state.range(0)));
  const auto& space = *s.space;
  const auto u = compressed_state(space);
  fem::StiffnessMatrix K(PETSC_COMM_WORLD, space);
  std::vector<double> r(space.n_dofs());
  for (auto _ : state) {
    std::fill(r.begin(), r.end(), 0.0);
    K.begin_assembly();
    fem::assemble_internal(space, s.problem.cell_material, u, r, &K);
    K.end_assembly();
    benchmark::DoNotOptimize(r.data());
  }
  Mat A = K.mat();
  state.counters["unknowns"] = space.n_dofs();
  state.counters["cells"] = s.mesh.n_cells();
  // Element kernel throughput (stress, tangent and scatter per P2 tetrahedron).
  state.counters["cells/s"] = benchmark::Counter(s.mesh.n_cells(), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["MDof/s"] = benchmark::Counter(space.n_dofs() * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["matrix_MB"] = solvers::aij_storage_mb(A);
  state.counters["peak_RSS_MB"] = peak_resident_mb();
}
BENCHMARK(BM_ResidualAndTangent)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ResidualOnly(benchmark::State& state) {
  scene::Scene& s = block(static_cast<int>(state.range(0)));
  const auto& space = *s.space;
  const auto u = compressed_state(space);
  std::vector<double> r(space.n_dofs());
  for (auto _ : state) {
    std::fill(r.begin(), r.end(), 0.0);
    fem::assemble_internal(space, s.problem.cell_material, u, r, nullptr);
    benchmark::DoNotOptimize(r.data());
  }
  state.counters["unknowns"] = space.n_dofs();
  state.counters["cells/s"] = benchmark::Counter(s.mesh.n_cells(), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["MDof/s"] = benchmark::Counter(space.n_dofs() * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ResidualOnly)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_MatMult(benchmark::State& state) {
  scene::Scene& s = block(static_cast<int>(state.range(0)));
  const auto& space = *s.space;
  fem::StiffnessMatrix K(PETSC_COMM_WORLD, space);
  K.begin_assembly();
  fem::assemble_internal(space, s.problem.cell_material, compressed_state(space), {}, &K);
  K.end_assembly();
  Mat A = K.mat();
  PetscVec x, y;
  MatCreateVecs(A, x.out(), y.out());
  VecSet(x, 1.0);
  for (auto _ : state) MatMult(A, x, y);
  state.counters["unknowns"] = space.n_dofs();
  state.counters["MDof/s"] = benchmark::Counter(space.n_dofs() * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MatMult)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
