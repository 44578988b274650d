// The main of the benchmarks that need nothing but PETSc set up: the allocator stiction uses,
// Google Benchmark's options, then one PETSc session around the runs.
#include <benchmark/benchmark.h>

#include "common/petsc.hpp"
#include "common/process_memory.hpp"

int main(int argc, char** argv) {
  stiction::restart_with_huge_pages_for_mapped_blocks(argv);  // as stiction does: the same allocator
  benchmark::Initialize(&argc, argv);
  int pargc = 1;
  stiction::PetscSession petsc(&pargc, &argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
