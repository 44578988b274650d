// Mesh refinement whole and in parts: what the parts' bookkeeping (records by global id, the
// edge numbering's scan, the ghost exchange) costs beside mesh::refine, which it reproduces
// bit for bit. The block with strips' level-0 mesh (Gmsh, built once) refined once or twice.
//
//   build/benchmarks/bench_mesh [--benchmark_filter=...]
//   mpirun -n 2 build/benchmarks/bench_mesh --benchmark_filter=InParts   # each process its part
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "builtin_scenes.hpp"
#include "common/petsc.hpp"
#include "fem/mesh_partition.hpp"
#include "mesh/local_mesh.hpp"

namespace {

using namespace stiction;

const mesh::Mesh& block_strips_level0() {
  static const std::unique_ptr<scene::Scene> s = harness::open_scene("block-strips", 0);
  return s->mesh;
}

void BM_RefineWhole(benchmark::State& state) {
  const mesh::Mesh& coarse = block_strips_level0();
  int cells = 0;
  for (auto _ : state) {
    const mesh::Mesh fine = mesh::refine(coarse, static_cast<int>(state.range(0)));
    cells = fine.n_cells();
    benchmark::DoNotOptimize(fine.coords.data());
  }
  state.counters["cells"] = cells;
  state.counters["cells/s"] = benchmark::Counter(cells, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RefineWhole)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Under mpirun each process refines its part of the level-0 mesh as PT-Scotch splits it;
// each process prints its own counters.
void BM_RefineInParts(benchmark::State& state) {
  const mesh::Mesh& coarse = block_strips_level0();
  const fem::MeshPartition partition = fem::partition_cells(PETSC_COMM_WORLD, coarse);
  const mesh::LocalMesh part = mesh::local_part(coarse, partition.cell_owner, partition.rank);
  int own = 0, held = 0, whole = 0;
  for (auto _ : state) {
    mesh::LocalMesh fine = mesh::refine_parts(PETSC_COMM_WORLD, part);
    for (int level = 2; level <= state.range(0); ++level) fine = mesh::refine_parts(PETSC_COMM_WORLD, fine);
    own = fine.n_own_cells, held = fine.mesh.n_cells(), whole = fine.n_global_cells;
    benchmark::DoNotOptimize(fine.mesh.coords.data());
  }
  state.counters["cells"] = whole;
  state.counters["own_cells"] = own;
  state.counters["held_cells"] = held;
  state.counters["cells/s"] = benchmark::Counter(whole, benchmark::Counter::kIsIterationInvariantRate);
}
// A fixed iteration count: Google Benchmark would choose one per process from its own
// timings, and processes that disagree would wait for each other in the exchange forever.
BENCHMARK(BM_RefineInParts)->Arg(1)->Arg(2)->Iterations(3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
