// Shared GoogleTest main: PETSc is initialised once per test process.
#include <gtest/gtest.h>

#include "common/petsc.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  int pargc = 1;
  char** pargv = argv;
  stiction::PetscSession petsc(&pargc, &pargv);
  return RUN_ALL_TESTS();
}
