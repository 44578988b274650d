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

// One process's rows of a distributed AIJ matrix in PETSc's MPIAIJ split: the diagonal
// part (columns of the process's own range, numbered from its first) and the off-diagonal
// part (global columns), each in compressed rows, columns ascending within a row.
struct SplitCsrArrays {
  std::vector<PetscInt> diagonal_start, diagonal_columns, off_diagonal_start, off_diagonal_columns;
  std::vector<PetscScalar> diagonal_values, off_diagonal_values;
};

// The square global_rows x global_rows MPIAIJ matrix of which this process owns `rows`
// consecutive rows, over the arrays without copying them (MatCreateMPIAIJWithSplitArrays):
// the matrix keeps them alive; PETSc renumbers the off-diagonal columns in place when it
// assembles. Its pattern is fixed (new nonzeros are an error).
Mat mpi_aij_over(MPI_Comm comm, PetscInt rows, PetscInt global_rows, SplitCsrArrays arrays);

}  // namespace stiction
