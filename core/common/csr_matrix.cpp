#include "common/csr_matrix.hpp"

namespace stiction {

namespace {

PetscErrorCode destroy_arrays(void* ctx) {
  delete static_cast<CsrArrays*>(ctx);
  return 0;
}

}  // namespace

Mat seq_aij_over(MPI_Comm comm, PetscInt rows, CsrArrays arrays) {
  PetscMPIInt size;
  MPI_Comm_size(comm, &size);
  if (size != 1) throw Error("compressed-row matrices are sequential: a single MPI process is supported so far");
  if (arrays.row_start->size() != static_cast<size_t>(rows) + 1 ||
      static_cast<size_t>(arrays.row_start->back()) != arrays.columns->size() ||
      arrays.columns->size() != arrays.values->size())
    throw Error("compressed-row matrix: array sizes disagree", ErrorKind::Internal);
  // MatCreateSeqAIJWithArrays takes non-const pointers; it never writes the pattern.
  auto* owned = new CsrArrays(std::move(arrays));
  Mat A = nullptr;
  PetscContainer container = nullptr;
  try {
    STICTION_PETSC(MatCreateSeqAIJWithArrays(comm, rows, rows, const_cast<PetscInt*>(owned->row_start->data()),
                                             const_cast<PetscInt*>(owned->columns->data()), owned->values->data(), &A));
    STICTION_PETSC(PetscContainerCreate(comm, &container));
    STICTION_PETSC(PetscContainerSetPointer(container, owned));
    STICTION_PETSC(PetscContainerSetUserDestroy(container, destroy_arrays));
  } catch (...) {
    if (!container) delete owned;
    PetscContainerDestroy(&container);
    MatDestroy(&A);
    throw;
  }
  // The matrix holds the only lasting reference to the container: the arrays go with it.
  STICTION_PETSC(PetscObjectCompose(reinterpret_cast<PetscObject>(A), "stiction_csr_arrays",
                                    reinterpret_cast<PetscObject>(container)));
  STICTION_PETSC(PetscContainerDestroy(&container));
  STICTION_PETSC(MatSetOption(A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  return A;
}

}  // namespace stiction
