#include "nonlinear/augmented_matrix.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace stiction::nonlinear {

namespace {

// The entries sorted by (row, col) with duplicates summed, as compressed rows of `rows` rows.
struct CompressedRows {
  std::vector<PetscInt> start, cols;
  std::vector<double> values;
};

CompressedRows compress(PetscInt rows, const SparseEntries& e) {
  std::vector<size_t> order(e.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return e.rows[a] != e.rows[b] ? e.rows[a] < e.rows[b] : e.cols[a] < e.cols[b];
  });
  CompressedRows c;
  c.start.assign(static_cast<size_t>(rows) + 1, 0);
  PetscInt last_r = -1, last_c = -1;
  for (size_t k : order) {
    if (e.rows[k] < 0 || e.rows[k] >= rows) throw Error("augmented matrix: entry row out of range", ErrorKind::Internal);
    if (e.rows[k] == last_r && e.cols[k] == last_c) {
      c.values.back() += e.values[k];
      continue;
    }
    last_r = e.rows[k], last_c = e.cols[k];
    c.cols.push_back(last_c);
    c.values.push_back(e.values[k]);
    ++c.start[static_cast<size_t>(last_r) + 1];
  }
  std::partial_sum(c.start.begin(), c.start.end(), c.start.begin());
  return c;
}

// Appends the sorted union of two sorted (col, value) rows, summing shared columns.
void merge_row(const PetscInt* ac, const PetscScalar* av, PetscInt an, const PetscInt* bc, const double* bv,
               PetscInt bn, std::vector<PetscInt>& cols, std::vector<PetscScalar>& vals) {
  PetscInt i = 0, j = 0;
  while (i < an || j < bn) {
    if (j == bn || (i < an && ac[i] < bc[j])) {
      cols.push_back(ac[i]), vals.push_back(av[i++]);
    } else if (i == an || bc[j] < ac[i]) {
      cols.push_back(bc[j]), vals.push_back(bv[j++]);
    } else {
      cols.push_back(ac[i]), vals.push_back(av[i++] + bv[j++]);
    }
  }
}

Mat matrix_from_csr(MPI_Comm comm, PetscInt rows, const std::vector<PetscInt>& start, const std::vector<PetscInt>& cols,
                    const std::vector<PetscScalar>& vals) {
  PetscMPIInt size;
  MPI_Comm_size(comm, &size);
  // The assembly core builds sequential matrices today; the distributed version will split
  // rows by ownership here.
  if (size != 1) throw Error("augmented matrix: a single MPI process is supported so far", ErrorKind::Input);
  Mat M;
  STICTION_PETSC(MatCreate(comm, &M));
  STICTION_PETSC(MatSetSizes(M, rows, rows, rows, rows));
  STICTION_PETSC(MatSetType(M, MATSEQAIJ));
  STICTION_PETSC(MatSeqAIJSetPreallocationCSR(M, start.data(), cols.data(), vals.data()));
  return M;
}

}  // namespace

Mat build_augmented_matrix(Mat A, PetscInt m, const SparseEntries& extra) {
  PetscInt n;
  STICTION_PETSC(MatGetSize(A, &n, nullptr));
  const PetscInt total = n + m;
  SparseEntries with_diagonal = extra;
  for (PetscInt r = n; r < total; ++r) with_diagonal.add(r, r, 0.0);
  const CompressedRows e = compress(total, with_diagonal);

  const PetscInt *ia, *ja;
  PetscInt n_rows;
  PetscBool done;
  STICTION_PETSC(MatGetRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n_rows, &ia, &ja, &done));
  if (!done) throw Error("augmented matrix: the tangent is not an AIJ matrix", ErrorKind::Internal);
  const PetscScalar* av;
  STICTION_PETSC(MatSeqAIJGetArrayRead(A, &av));
  std::vector<PetscInt> start(static_cast<size_t>(total) + 1, 0), cols;
  std::vector<PetscScalar> vals;
  cols.reserve(static_cast<size_t>(ia[n]) + e.cols.size());
  vals.reserve(cols.capacity());
  for (PetscInt r = 0; r < total; ++r) {
    const PetscInt a0 = r < n ? ia[r] : 0, an = r < n ? ia[r + 1] - ia[r] : 0;
    merge_row(ja + a0, av + a0, an, e.cols.data() + e.start[r], e.values.data() + e.start[r],
              e.start[r + 1] - e.start[r], cols, vals);
    start[static_cast<size_t>(r) + 1] = static_cast<PetscInt>(cols.size());
  }
  STICTION_PETSC(MatSeqAIJRestoreArrayRead(A, &av));
  STICTION_PETSC(MatRestoreRowIJ(A, 0, PETSC_FALSE, PETSC_FALSE, &n_rows, &ia, &ja, &done));
  Mat M = matrix_from_csr(PetscObjectComm(reinterpret_cast<PetscObject>(A)), total, start, cols, vals);
  PetscInt bs;
  STICTION_PETSC(MatGetBlockSize(A, &bs));
  if (bs > 1 && m % bs == 0) STICTION_PETSC(MatSetBlockSize(M, bs));
  return M;
}

Mat build_sparse_matrix(MPI_Comm comm, PetscInt m, const SparseEntries& entries) {
  SparseEntries with_diagonal = entries;
  for (PetscInt r = 0; r < m; ++r) with_diagonal.add(r, r, 0.0);
  const CompressedRows e = compress(m, with_diagonal);
  return matrix_from_csr(comm, m, e.start, e.cols, std::vector<PetscScalar>(e.values.begin(), e.values.end()));
}

}  // namespace stiction::nonlinear
