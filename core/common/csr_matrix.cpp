#include "common/csr_matrix.hpp"

namespace stiction {

namespace {

template <class Arrays>
PetscErrorCode destroy_arrays(void* ctx) {
  delete static_cast<Arrays*>(ctx);
  return 0;
}

// Attaches the arrays to A (deleted with it).
template <class Arrays>
void keep_with(Mat A, Arrays* arrays) {
  PetscContainer container = nullptr;
  try {
    STICTION_PETSC(PetscContainerCreate(PetscObjectComm(reinterpret_cast<PetscObject>(A)), &container));
    STICTION_PETSC(PetscContainerSetPointer(container, arrays));
    STICTION_PETSC(PetscContainerSetUserDestroy(container, destroy_arrays<Arrays>));
  } catch (...) {
    if (!container) delete arrays;
    PetscContainerDestroy(&container);
    throw;
  }
  // The matrix holds the only lasting reference to the container: the arrays go with it.
  STICTION_PETSC(PetscObjectCompose(reinterpret_cast<PetscObject>(A), "stiction_csr_arrays",
                                    reinterpret_cast<PetscObject>(container)));
  STICTION_PETSC(PetscContainerDestroy(&container));
}

// The matrix create(arrays) makes over the arrays, which it then keeps alive; its pattern
// is fixed.
template <class Arrays, class Create>
Mat matrix_over(Arrays arrays, Create create) {
  auto* owned = new Arrays(std::move(arrays));
  Mat A = nullptr;
  try {
    A = create(*owned);
  } catch (...) {
    delete owned;
    throw;
  }
  try {
    keep_with(A, owned);
  } catch (...) {
    MatDestroy(&A);
    throw;
  }
  STICTION_PETSC(MatSetOption(A, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  return A;
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
  return matrix_over(std::move(arrays), [&](CsrArrays& a) {
    // MatCreateSeqAIJWithArrays takes non-const pointers; it never writes the pattern.
    Mat A = nullptr;
    STICTION_PETSC(MatCreateSeqAIJWithArrays(comm, rows, rows, const_cast<PetscInt*>(a.row_start->data()),
                                             const_cast<PetscInt*>(a.columns->data()), a.values->data(), &A));
    return A;
  });
}

Mat mpi_aij_over(MPI_Comm comm, PetscInt rows, PetscInt global_rows, SplitCsrArrays arrays) {
  if (arrays.diagonal_start.size() != static_cast<size_t>(rows) + 1 ||
      arrays.off_diagonal_start.size() != static_cast<size_t>(rows) + 1 ||
      static_cast<size_t>(arrays.diagonal_start.back()) > arrays.diagonal_columns.size() ||
      arrays.diagonal_columns.size() != arrays.diagonal_values.size() ||
      static_cast<size_t>(arrays.off_diagonal_start.back()) > arrays.off_diagonal_columns.size() ||
      arrays.off_diagonal_columns.size() != arrays.off_diagonal_values.size())
    throw Error("split compressed-row matrix: array sizes disagree", ErrorKind::Internal);
  return matrix_over(std::move(arrays), [&](SplitCsrArrays& a) {
    Mat A = nullptr;
    STICTION_PETSC(MatCreateMPIAIJWithSplitArrays(comm, rows, rows, global_rows, global_rows, a.diagonal_start.data(),
                                                  a.diagonal_columns.data(), a.diagonal_values.data(),
                                                  a.off_diagonal_start.data(), a.off_diagonal_columns.data(),
                                                  a.off_diagonal_values.data(), &A));
    return A;
  });
}

}  // namespace stiction
