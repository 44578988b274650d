#include "nonlinear/augmented_matrix.hpp"

#include "common/csr_matrix.hpp"

#include <algorithm>
#include <memory>
#include <numeric>
#include <vector>

namespace stiction::nonlinear {

namespace {

// The entries sorted by (row, col) with duplicates summed, as compressed rows of `rows` rows;
// rows from `diagonal_from` on also get their diagonal (a zero when no entry is there).
struct CompressedRows {
  std::vector<PetscInt> start, cols;
  std::vector<PetscScalar> values;
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

// The number of distinct columns in the union of two sorted rows.
PetscInt union_size(const PetscInt* a, PetscInt an, const PetscInt* b, PetscInt bn) {
  PetscInt i = 0, j = 0, count = 0;
  while (i < an || j < bn) {
    ++count;
    if (j == bn || (i < an && a[i] < b[j]))
      ++i;
    else if (i == an || b[j] < a[i])
      ++j;
    else
      ++i, ++j;
  }
  return count;
}

}  // namespace

Mat build_augmented_matrix(MPI_Comm comm, CsrArrays tangent, PetscInt m, const SparseEntries& extra,
                           PetscInt block_size) {
  const std::vector<PetscInt>& ia = *tangent.row_start;
  const std::vector<PetscInt>& ja = *tangent.columns;
  const PetscInt n = static_cast<PetscInt>(ia.size()) - 1, total = n + m;
  const CompressedRows e = compress(total, extra, n);
  auto a_row = [&](PetscInt r, PetscInt& first, PetscInt& count) {
    first = r < n ? ia[r] : 0;
    count = r < n ? ia[r + 1] - ia[r] : 0;
  };

  auto start = std::make_shared<std::vector<PetscInt>>(static_cast<size_t>(total) + 1, 0);
  for (PetscInt r = 0; r < total; ++r) {
    PetscInt a0, an;
    a_row(r, a0, an);
    (*start)[r + 1] = (*start)[r] + union_size(ja.data() + a0, an, e.cols.data() + e.start[r], e.start[r + 1] - e.start[r]);
  }
  // The tangent's values become the augmented matrix's: merged in place from the last row
  // back. Row r of the result starts at or after row r of the tangent and holds at least
  // as many entries, so every write lands on a slot already read or at a higher index than
  // any tangent value still to be read.
  std::vector<PetscScalar>& vals = *tangent.values;
  vals.resize(static_cast<size_t>(start->back()));
  auto cols = std::make_shared<std::vector<PetscInt>>(static_cast<size_t>(start->back()));
  for (PetscInt r = total - 1; r >= 0; --r) {
    PetscInt a0, an;
    a_row(r, a0, an);
    PetscInt i = a0 + an - 1, j = e.start[r + 1] - 1, k = (*start)[r + 1] - 1;
    const PetscInt i_end = a0 - 1, j_end = e.start[r] - 1;
    for (; k >= (*start)[r]; --k) {
      if (j == j_end || (i != i_end && ja[i] > e.cols[j])) {
        (*cols)[k] = ja[i], vals[k] = vals[i], --i;
      } else if (i == i_end || e.cols[j] > ja[i]) {
        (*cols)[k] = e.cols[j], vals[k] = e.values[j], --j;
      } else {
        (*cols)[k] = ja[i], vals[k] = vals[i] + e.values[j], --i, --j;
      }
    }
  }
  Mat M = seq_aij_over(comm, total, {start, cols, tangent.values});
  if (block_size > 1 && m % block_size == 0) STICTION_PETSC(MatSetBlockSize(M, block_size));
  return M;
}

namespace {

// Appends the union of two rows to cols and values in ascending column order (values
// summed where both have a column); row a's k-th column is a_column(k).
template <class ColumnOfA>
void append_union(PetscInt an, ColumnOfA a_column, const PetscScalar* a_values, PetscInt bn, const PetscInt* b_cols,
                  const PetscScalar* b_values, std::vector<PetscInt>& cols, std::vector<PetscScalar>& values) {
  PetscInt i = 0, j = 0;
  while (i < an || j < bn) {
    const PetscInt a = i < an ? a_column(i) : 0;
    if (j == bn || (i < an && a < b_cols[j])) {
      cols.push_back(a), values.push_back(a_values[i]), ++i;
    } else if (i == an || b_cols[j] < a) {
      cols.push_back(b_cols[j]), values.push_back(b_values[j]), ++j;
    } else {
      cols.push_back(a), values.push_back(a_values[i] + b_values[j]), ++i, ++j;
    }
  }
}

// The entries of e (in the layout's local index) whose rows this rank owns, in PETSc's
// indices: its own in the order computed, then those the other ranks computed for its rows,
// by sending rank (a fixed order: the sums of duplicates are the same on every run). The
// entries travel in PETSc's indices and find their owner by its range: a process's local
// index means nothing to another over mesh parts, and a part may compute a row whose owner
// it cannot tell (a contact surface node away from its own cells).
SparseEntries entries_of_owned_rows(const fem::DofLayout& layout, const SparseEntries& e) {
  const MPI_Comm comm = layout.comm();
  int size = 1, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  std::vector<PetscInt> first(static_cast<size_t>(size) + 1, layout.n_total());
  const PetscInt my_first = layout.first_owned();
  MPI_Allgather(&my_first, 1, MPIU_INT, first.data(), 1, MPIU_INT, comm);
  SparseEntries out;
  std::vector<int> owner(e.size());
  std::vector<int> send_count(static_cast<size_t>(size), 0), recv_count(static_cast<size_t>(size));
  SparseEntries global;
  for (size_t k = 0; k < e.size(); ++k) {
    const PetscInt row = layout.global(e.rows[k]);
    global.add(row, layout.global(e.cols[k]), e.values[k]);
    owner[k] = static_cast<int>(std::upper_bound(first.begin(), first.end() - 1, row) - first.begin()) - 1;
    if (owner[k] == rank) out.add(global.rows[k], global.cols[k], global.values[k]);
    else ++send_count[static_cast<size_t>(owner[k])];
  }
  std::vector<int> send_first(static_cast<size_t>(size) + 1, 0), recv_first(static_cast<size_t>(size) + 1, 0);
  std::partial_sum(send_count.begin(), send_count.end(), send_first.begin() + 1);
  MPI_Alltoall(send_count.data(), 1, MPI_INT, recv_count.data(), 1, MPI_INT, comm);
  std::partial_sum(recv_count.begin(), recv_count.end(), recv_first.begin() + 1);
  SparseEntries send;
  send.rows.resize(static_cast<size_t>(send_first.back()));
  send.cols.resize(send.rows.size());
  send.values.resize(send.rows.size());
  std::vector<int> next(send_first.begin(), send_first.end() - 1);
  for (size_t k = 0; k < e.size(); ++k) {
    if (owner[k] == rank) continue;
    const size_t at = static_cast<size_t>(next[static_cast<size_t>(owner[k])]++);
    send.rows[at] = global.rows[k], send.cols[at] = global.cols[k], send.values[at] = global.values[k];
  }
  const size_t n_own = out.size(), n_received = static_cast<size_t>(recv_first.back());
  out.rows.resize(n_own + n_received);
  out.cols.resize(n_own + n_received);
  out.values.resize(n_own + n_received);
  MPI_Alltoallv(send.rows.data(), send_count.data(), send_first.data(), MPIU_INT,
                out.rows.data() + n_own, recv_count.data(), recv_first.data(), MPIU_INT, comm);
  MPI_Alltoallv(send.cols.data(), send_count.data(), send_first.data(), MPIU_INT,
                out.cols.data() + n_own, recv_count.data(), recv_first.data(), MPIU_INT, comm);
  MPI_Alltoallv(send.values.data(), send_count.data(), send_first.data(), MPIU_SCALAR,
                out.values.data() + n_own, recv_count.data(), recv_first.data(), MPIU_SCALAR, comm);
  return out;
}

// This rank's rows of the constraint blocks, compressed (local rows, PETSc's columns,
// duplicates summed in the order added, as on one rank), with the multiplier diagonals.
CompressedRows owned_constraint_rows(const fem::DofLayout& layout, PetscInt n_u, const SparseEntries& extra) {
  const PetscInt first = layout.first_owned();
  SparseEntries owned;
  for (PetscInt a = n_u; a < layout.n_held(); ++a)
    if (layout.owns(a)) owned.add(layout.global(a) - first, layout.global(a), 0.0);
  const SparseEntries mine = entries_of_owned_rows(layout, extra);
  for (size_t k = 0; k < mine.size(); ++k) owned.add(mine.rows[k] - first, mine.cols[k], mine.values[k]);
  return compress(layout.n_owned(), owned, layout.n_owned());
}

// Read access to an MPIAIJ matrix's local split: the diagonal part (local columns) and the
// off-diagonal part (compressed columns, ascending through column_map), as CSR arrays;
// returned to PETSc on destruction.
class SplitRowsView {
public:
  SplitRowsView(Mat A, PetscInt n_rows) {
    STICTION_PETSC(MatMPIAIJGetSeqAIJ(A, &parts_[0], &parts_[1], &column_map));
    try {
      for (int k = 0; k < 2; ++k) {
        PetscInt n;
        PetscBool done;
        STICTION_PETSC(MatGetRowIJ(parts_[k], 0, PETSC_FALSE, PETSC_FALSE, &n, &start[k], &cols[k], &done));
        if (!done || n != n_rows)
          throw Error("augmented matrix: the tangent's rows are not this rank's", ErrorKind::Internal);
        STICTION_PETSC(MatSeqAIJGetArrayRead(parts_[k], &values[k]));
      }
    } catch (...) {
      release();  // a constructor that throws gets no destructor call
      throw;
    }
  }
  ~SplitRowsView() { release(); }
  SplitRowsView(const SplitRowsView&) = delete;
  SplitRowsView& operator=(const SplitRowsView&) = delete;

  const PetscInt* column_map = nullptr;
  const PetscInt *start[2] = {}, *cols[2] = {};  // [0] diagonal part, [1] off-diagonal part
  const PetscScalar* values[2] = {};

private:
  // Returns what was taken (PETSc's calls cannot fail here once the matching Get succeeded).
  void release() {
    for (int k = 0; k < 2; ++k) {
      PetscInt n;
      PetscBool done;
      if (values[k]) MatSeqAIJRestoreArrayRead(parts_[k], &values[k]);
      if (start[k]) MatRestoreRowIJ(parts_[k], 0, PETSC_FALSE, PETSC_FALSE, &n, &start[k], &cols[k], &done);
      values[k] = nullptr, start[k] = cols[k] = nullptr;
    }
  }

  Mat parts_[2] = {};
};

// Each owned row of the tangent (its split) merged with the same row of the constraint
// entries e (PETSc's columns) into new split arrays.
SplitCsrArrays merge_split_rows(const SplitRowsView& t, const CompressedRows& e, PetscInt first, PetscInt n_owned) {
  SplitCsrArrays out;
  out.diagonal_start.assign(1, 0);
  out.off_diagonal_start.assign(1, 0);
  out.diagonal_columns.reserve(static_cast<size_t>(t.start[0][n_owned]) + e.cols.size());
  out.diagonal_values.reserve(out.diagonal_columns.capacity());
  out.off_diagonal_columns.reserve(static_cast<size_t>(t.start[1][n_owned]) + e.cols.size());
  out.off_diagonal_values.reserve(out.off_diagonal_columns.capacity());
  std::vector<PetscInt> b_cols;
  std::vector<PetscScalar> b_values;
  for (PetscInt r = 0; r < n_owned; ++r) {
    const PetscInt* c = e.cols.data() + e.start[r];
    const PetscScalar* v = e.values.data() + e.start[r];
    const PetscInt m = e.start[r + 1] - e.start[r];
    const PetscInt lo = std::lower_bound(c, c + m, first) - c, hi = std::lower_bound(c, c + m, first + n_owned) - c;
    b_cols.clear();
    for (PetscInt k = lo; k < hi; ++k) b_cols.push_back(c[k] - first);
    const PetscInt* d_cols = t.cols[0] + t.start[0][r];
    append_union(t.start[0][r + 1] - t.start[0][r], [&](PetscInt k) { return d_cols[k]; }, t.values[0] + t.start[0][r],
                 hi - lo, b_cols.data(), v + lo, out.diagonal_columns, out.diagonal_values);
    out.diagonal_start.push_back(static_cast<PetscInt>(out.diagonal_columns.size()));
    b_cols.assign(c, c + lo);
    b_cols.insert(b_cols.end(), c + hi, c + m);
    b_values.assign(v, v + lo);
    b_values.insert(b_values.end(), v + hi, v + m);
    const PetscInt* o_cols = t.cols[1] + t.start[1][r];
    append_union(t.start[1][r + 1] - t.start[1][r], [&](PetscInt k) { return t.column_map[o_cols[k]]; },
                 t.values[1] + t.start[1][r], static_cast<PetscInt>(b_cols.size()), b_cols.data(), b_values.data(),
                 out.off_diagonal_columns, out.off_diagonal_values);
    out.off_diagonal_start.push_back(static_cast<PetscInt>(out.off_diagonal_columns.size()));
  }
  return out;
}

}  // namespace

Mat build_distributed_augmented_matrix(Mat tangent, const fem::DofLayout& layout, PetscInt n_u,
                                       const SparseEntries& extra, PetscInt block_size) {
  const PetscInt first = layout.first_owned(), n_owned = layout.n_owned(), n_total = layout.n_total();
  // Straight from and into the MPIAIJ split, without MatGetRow or MatSetValues: the new
  // matrix is made over the merged arrays.
  SplitCsrArrays merged;
  {
    const CompressedRows e = owned_constraint_rows(layout, n_u, extra);
    const SplitRowsView t(tangent, n_owned);
    merged = merge_split_rows(t, e, first, n_owned);
  }
  Mat A = mpi_aij_over(layout.comm(), n_owned, n_total, std::move(merged));
  if (block_size > 1 && n_owned % block_size == 0 && n_total % block_size == 0)
    STICTION_PETSC(MatSetBlockSize(A, block_size));
  return A;
}

Mat build_sparse_matrix(MPI_Comm comm, PetscInt m, const SparseEntries& entries, Diagonal diagonal) {
  CompressedRows e = compress(m, entries, diagonal == Diagonal::Keep ? 0 : m);
  return seq_aij_over(comm, m,
                      {std::make_shared<const std::vector<PetscInt>>(std::move(e.start)),
                       std::make_shared<const std::vector<PetscInt>>(std::move(e.cols)),
                       std::make_shared<std::vector<PetscScalar>>(std::move(e.values))});
}

Mat build_block_matrix(const fem::DofLayout& layout, PetscInt first, PetscInt m, const SparseEntries& entries,
                       Diagonal diagonal) {
  if (layout.identity()) return build_sparse_matrix(layout.comm(), m, entries, diagonal);
  const std::vector<PetscInt> number = layout.block_numbering(first, first + m);
  // This rank's rows of the block are consecutive in its numbering: [row_first, row_first + n_owned).
  PetscInt n_owned = 0, row_first = m;
  for (PetscInt k = 0; k < m; ++k)
    if (layout.owns(first + k)) ++n_owned, row_first = std::min(row_first, number[static_cast<size_t>(k)]);
  // Preallocation counts duplicates (an upper bound), capped by the row's room.
  const PetscInt with_diagonal = diagonal == Diagonal::Keep ? 1 : 0;
  std::vector<PetscInt> d_nnz(static_cast<size_t>(n_owned), with_diagonal), o_nnz(static_cast<size_t>(n_owned), 0);
  for (size_t e = 0; e < entries.size(); ++e) {
    if (!layout.owns(first + entries.rows[e])) continue;
    const PetscInt r = number[static_cast<size_t>(entries.rows[e])] - row_first;
    const PetscInt c = number[static_cast<size_t>(entries.cols[e])];
    ++(c >= row_first && c < row_first + n_owned ? d_nnz : o_nnz)[static_cast<size_t>(r)];
  }
  for (PetscInt r = 0; r < n_owned; ++r) {
    d_nnz[static_cast<size_t>(r)] = std::min(d_nnz[static_cast<size_t>(r)], n_owned);
    o_nnz[static_cast<size_t>(r)] = std::min(o_nnz[static_cast<size_t>(r)], m - n_owned);
  }
  Mat M;
  STICTION_PETSC(MatCreateAIJ(layout.comm(), n_owned, n_owned, m, m, 0, d_nnz.data(), 0, o_nnz.data(), &M));
  const PetscScalar zero = 0;
  for (PetscInt r = row_first; with_diagonal && r < row_first + n_owned; ++r)
    STICTION_PETSC(MatSetValues(M, 1, &r, 1, &r, &zero, ADD_VALUES));
  for (size_t e = 0; e < entries.size(); ++e) {
    if (!layout.owns(first + entries.rows[e])) continue;
    const PetscInt r = number[static_cast<size_t>(entries.rows[e])], c = number[static_cast<size_t>(entries.cols[e])];
    STICTION_PETSC(MatSetValues(M, 1, &r, 1, &c, &entries.values[e], ADD_VALUES));
  }
  STICTION_PETSC(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  return M;
}

}  // namespace stiction::nonlinear
