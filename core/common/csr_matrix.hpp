#pragma once
// A sequential AIJ matrix stored in compressed-row arrays the caller built, without the copy
// that MatSeqAIJSetPreallocationCSR makes: the arrays become the matrix's storage, and the
// matrix keeps them alive (shared ownership), so they outlive every reference PETSc holds.
// The row starts and columns may be shared by several matrices of one pattern.
#include <memory>
#include <vector>

#include "common/petsc.hpp"

namespace stiction {

struct CsrArrays {
  std::shared_ptr<const std::vector<PetscInt>> row_start;  // rows + 1 entries
  std::shared_ptr<const std::vector<PetscInt>> columns;    // sorted within each row
  std::shared_ptr<std::vector<PetscScalar>> values;
};

// Square, rows x rows. PETSc reads the arrays in place; it never changes the pattern of a
// matrix made this way (new nonzeros are an error).
Mat seq_aij_over(MPI_Comm comm, PetscInt rows, CsrArrays arrays);

}  // namespace stiction
