#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "common/process_memory.hpp"

namespace {

using stiction::resident_mb;

// A large block freed leaves the resident set (PetscSession set the allocator so, in this
// test binary as in stiction). With the settings SuperLU_dist's CombBLAS leaves in every
// program that loads PETSc (no mapped blocks, no trimming) the 256 MB stayed resident.
TEST(ProcessMemory, AFreedLargeBlockLeavesTheResidentSet) {
  constexpr std::size_t bytes = std::size_t{256} << 20;
  const double before = resident_mb();
  char* block = static_cast<char*>(std::malloc(bytes));
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, bytes);
  asm volatile("" : : "g"(block) : "memory");  // the writes happen: the block is not optimised away
  const double written = resident_mb();
  std::free(block);
  const double after = resident_mb();
  EXPECT_GT(written - before, 200.0);  // the block was resident once written
  EXPECT_LT(after - before, 20.0) << "resident before " << before << " MB, written " << written << " MB, freed "
                                  << after << " MB";
}

}  // namespace
