#include "nonlinear/augmented_matrix.hpp"

#include <algorithm>
#include <numeric>
#include <vector>

namespace stiction::nonlinear {

namespace {

// The entries sorted by (row, col) with duplicates summed, as compressed rows of `rows` rows;
// rows from `diagonal_from` on also get their diagonal (a zero when no entry is there).
struct CompressedRows {
  std::vector<PetscInt> start, cols;
  std::vector<double> values;
};

// A counting sort by row, then a stable sort by column within each row (duplicates summed
// in the order they were added). An index sort over all entries took 21% of a
// hertz-spheres-3d level-1 run (perf): 3D contact adds tens of millions of entries.
CompressedRows compress(PetscInt rows, const SparseEntries& e, PetscInt diagonal_from) {
  const size_t n_rows = static_cast<size_t>(rows);
  std::vector<size_t> fill(n_rows + 1, 0);
  for (size_t k = 0; k < e.size(); ++k) {
    if (e.rows[k] < 0 || e.rows[k] >= rows) throw Error("augmented matrix: entry row out of range", ErrorKind::Internal);
    ++fill[static_cast<size_t>(e.rows[k]) + 1];
  }
  for (size_t r = static_cast<size_t>(std::max<PetscInt>(diagonal_from, 0)); r < n_rows; ++r) ++fill[r + 1];
  std::partial_sum(fill.begin(), fill.end(), fill.begin());
  std::vector<std::pair<PetscInt, double>> sorted(fill[n_rows]);
  std::vector<size_t> next(fill.begin(), fill.end() - 1);
  for (size_t r = static_cast<size_t>(std::max<PetscInt>(diagonal_from, 0)); r < n_rows; ++r)
    sorted[next[r]++] = {static_cast<PetscInt>(r), 0.0};
  for (size_t k = 0; k < e.size(); ++k) sorted[next[static_cast<size_t>(e.rows[k])]++] = {e.cols[k], e.values[k]};
  CompressedRows c;
  c.start.assign(n_rows + 1, 0);
  c.cols.reserve(sorted.size());
  c.values.reserve(sorted.size());
  for (size_t r = 0; r < n_rows; ++r) {
    const auto first = sorted.begin() + static_cast<std::ptrdiff_t>(fill[r]);
    const auto last = sorted.begin() + static_cast<std::ptrdiff_t>(fill[r + 1]);
    std::stable_sort(first, last, [](const auto& a, const auto& b) { return a.first < b.first; });
    const size_t row_start = c.cols.size();
    for (auto it = first; it != last; ++it) {
      if (c.cols.size() > row_start && c.cols.back() == it->first) {
        c.values.back() += it->second;
        continue;
      }
      c.cols.push_back(it->first);
      c.values.push_back(it->second);
    }
    c.start[r + 1] = static_cast<PetscInt>(c.cols.size());
  }
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
  const CompressedRows e = compress(total, extra, n);

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
  const CompressedRows e = compress(m, entries, 0);
  return matrix_from_csr(comm, m, e.start, e.cols, std::vector<PetscScalar>(e.values.begin(), e.values.end()));
}

}  // namespace stiction::nonlinear
