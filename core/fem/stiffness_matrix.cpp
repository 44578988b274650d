#include "fem/stiffness_matrix.hpp"

#include <algorithm>
#include <numeric>

#include "common/csr_matrix.hpp"
#include "common/error.hpp"

namespace stiction::fem {

StiffnessMatrix::StiffnessMatrix(MPI_Comm comm, const FieldSpace& space) : space_(&space), dim_(space.dim()), comm_(comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size != 1) throw Error("stiffness matrix: several ranks need a DofLayout", ErrorKind::Internal);
  build_node_graph();
  build_row_starts();
  create_matrix();
}

StiffnessMatrix::StiffnessMatrix(const DofLayout& layout, const FieldSpace& space)
    : space_(&space), layout_(&layout), dim_(space.dim()), comm_(layout.comm()) {
  build_node_graph();
  if (distributed()) {
    create_distributed_matrix();
    return;
  }
  build_row_starts();
  create_matrix();
}

void StiffnessMatrix::build_node_graph() {
  const FieldSpace& space = *space_;
  const int nn = space.n_nodes(), npc = space.nodes_per_cell(), nc = space.mesh().n_cells();
  const int nv = space.n_vertices();

  // Node -> cells incidence, then each node's sorted, unique neighbours.
  std::vector<int> cell_nodes(static_cast<size_t>(nc) * npc), first(nn + 1, 0), incident;
  for (int c = 0; c < nc; ++c) {
    space.cell_nodes(c, &cell_nodes[static_cast<size_t>(c) * npc]);
    for (int k = 0; k < npc; ++k) ++first[cell_nodes[static_cast<size_t>(c) * npc + k] + 1];
  }
  for (int n = 0; n < nn; ++n) first[n + 1] += first[n];
  incident.resize(first[nn]);
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (int c = 0; c < nc; ++c)
    for (int k = 0; k < npc; ++k) incident[fill[cell_nodes[static_cast<size_t>(c) * npc + k]]++] = c;
  offsets_.assign(1, 0);
  std::vector<int> row;
  for (int n = 0; n < nn; ++n) {
    row.clear();
    for (int i = first[n]; i < first[n + 1]; ++i)
      row.insert(row.end(), &cell_nodes[static_cast<size_t>(incident[i]) * npc],
                 &cell_nodes[static_cast<size_t>(incident[i]) * npc] + npc);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    neighbours_.insert(neighbours_.end(), row.begin(), row.end());
    offsets_.push_back(static_cast<int>(neighbours_.size()));
    vertex_degree_.push_back(static_cast<int>(std::lower_bound(row.begin(), row.end(), nv) - row.begin()));
  }
  // A node is on a mixed body when its vertices carry a pressure (bodies share no node).
  mixed_.assign(nn, 0);
  for (int n = 0; n < nn; ++n) {
    const int v = n < nv ? n : space.edges().edges[n - nv][0];
    mixed_[n] = space.pressure_dof(v) >= 0;
  }
}

void StiffnessMatrix::build_row_starts() {
  const FieldSpace& space = *space_;
  const int nn = space.n_nodes(), nv = space.n_vertices(), d = dim_;
  // Row lengths in global row order: displacement rows, then pressure rows.
  const PetscInt n_rows = space.n_dofs();
  std::vector<PetscInt> nnz(n_rows);
  for (int a = 0; a < nn; ++a) {
    const PetscInt len = static_cast<PetscInt>(d) * degree(a) + (mixed_[a] ? vertex_degree_[a] : 0);
    for (int i = 0; i < d; ++i) nnz[static_cast<size_t>(a) * d + i] = len;
    if (a < nv && space.pressure_dof(a) >= 0) nnz[space.pressure_dof(a)] = len;
  }
  auto row_start = std::make_shared<std::vector<PetscInt>>(n_rows + 1, 0);
  for (PetscInt r = 0; r < n_rows; ++r) (*row_start)[r + 1] = (*row_start)[r] + nnz[r];
  std::vector<PetscInt>().swap(nnz);
  row_start_ = std::move(row_start);
}

void StiffnessMatrix::build_columns() {
  // The columns of every row, written node by node in the documented layout.
  const std::vector<PetscInt>& row_start = *row_start_;
  const int nn = space_->n_nodes(), nv = space_->n_vertices();
  auto columns = std::make_shared<std::vector<PetscInt>>(static_cast<size_t>(row_start.back()));
  std::vector<PetscInt> cols;
  for (int a = 0; a < nn; ++a) {
    row_columns(a, cols);
    auto put = [&](PetscInt row) { std::copy(cols.begin(), cols.end(), columns->begin() + row_start[row]); };
    for (int i = 0; i < dim_; ++i) put(static_cast<PetscInt>(a) * dim_ + i);
    if (a < nv && space_->pressure_dof(a) >= 0) put(space_->pressure_dof(a));
  }
  if (!layout_checked_) {
    for (size_t r = 0; r + 1 < row_start.size(); ++r)
      if (!std::is_sorted(columns->begin() + row_start[r], columns->begin() + row_start[r + 1]))
        throw Error("stiffness matrix: the row layout is not in column order", ErrorKind::Internal);
    layout_checked_ = true;
  }
  columns_ = std::move(columns);
}

// The rows of owned node a in PETSc's numbering (its components, then its pressure).
int StiffnessMatrix::node_rows(int a, PetscInt* rows) const {
  int n = 0;
  for (int i = 0; i < dim_; ++i) rows[n++] = layout_->global(static_cast<PetscInt>(a) * dim_ + i);
  if (a < space_->n_vertices() && space_->pressure_dof(a) >= 0) rows[n++] = layout_->global(space_->pressure_dof(a));
  return n;
}

// Node a's columns in PETSc's numbering, ascending, and for each entry of row_columns its
// place there (entry k is sorted[place[k]]).
void StiffnessMatrix::sorted_columns(int a, std::vector<PetscInt>& sorted, std::vector<int>& place) const {
  std::vector<PetscInt> cols;
  row_columns(a, cols);
  for (PetscInt& c : cols) c = layout_->global(c);
  std::vector<int> order(cols.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return cols[x] < cols[y]; });
  sorted.resize(cols.size());
  place.resize(cols.size());
  for (size_t k = 0; k < order.size(); ++k) sorted[k] = cols[order[k]], place[order[k]] = static_cast<int>(k);
}

// The slots of every owned node's neighbours and its rows' lengths in the two parts; the
// node graph keeps the owned nodes only (the others' rows are assembled elsewhere).
void StiffnessMatrix::lay_out_owned_rows(std::vector<PetscInt>& d_nnz, std::vector<PetscInt>& o_nnz) {
  const DofLayout& L = *layout_;
  const PetscInt first = L.first_owned(), n_owned = L.n_owned();
  const int nn = space_->n_nodes(), d = dim_;
  auto on_rank = [&](PetscInt g) { return g >= first && g < first + n_owned; };
  d_nnz.assign(static_cast<size_t>(n_owned), 0);
  o_nnz.assign(static_cast<size_t>(n_owned), 0);
  std::vector<int> offsets(nn + 1, 0), neighbours, place, slot;
  std::vector<PetscInt> sorted, rows(4);
  column_slot_.clear();
  pressure_slot_.clear();
  for (int a = 0; a < nn; ++a) {
    offsets[a + 1] = offsets[a];
    if (!L.owns(static_cast<PetscInt>(a) * d)) continue;
    sorted_columns(a, sorted, place);
    // Sorted entry k's offset in its part: PETSc keeps each part's columns ascending.
    slot.resize(sorted.size());
    int n_diagonal = 0, n_off = 0;
    for (size_t k = 0; k < sorted.size(); ++k) slot[k] = on_rank(sorted[k]) ? n_diagonal++ : -1 - n_off++;
    const int deg = degree(a);
    for (int j = 0; j < deg; ++j) {
      const int s0 = slot[place[static_cast<size_t>(j) * d]];
      for (int k = 1; k < d; ++k)  // a neighbour's components are consecutive in one part
        if (slot[place[static_cast<size_t>(j) * d + k]] != (s0 >= 0 ? s0 + k : s0 - k))
          throw Error("stiffness matrix: a node's components are not consecutive columns", ErrorKind::Internal);
      neighbours.push_back(neighbours_[offsets_[a] + j]);
      column_slot_.push_back(s0);
      pressure_slot_.push_back(mixed_[a] && j < vertex_degree_[a] ? slot[place[static_cast<size_t>(d) * deg + j]] : 0);
    }
    offsets[a + 1] = offsets[a] + deg;
    for (int r = 0, n = node_rows(a, rows.data()); r < n; ++r) {
      d_nnz[static_cast<size_t>(rows[r] - first)] = n_diagonal;
      o_nnz[static_cast<size_t>(rows[r] - first)] = n_off;
    }
  }
  offsets_ = std::move(offsets);
  neighbours_ = std::move(neighbours);
}

// The matrix over split arrays written from the node graph: every owned row's columns
// (zeros), ascending within each part. The slots are laid out at the first call.
void StiffnessMatrix::create_distributed_matrix() {
  const DofLayout& L = *layout_;
  const PetscInt first = L.first_owned(), n_owned = L.n_owned(), n_total = L.n_total();
  if (!rows_laid_out_) lay_out_owned_rows(diagonal_length_, off_diagonal_length_);
  rows_laid_out_ = true;
  SplitCsrArrays pattern;
  pattern.diagonal_start.assign(static_cast<size_t>(n_owned) + 1, 0);
  pattern.off_diagonal_start.assign(static_cast<size_t>(n_owned) + 1, 0);
  for (PetscInt r = 0; r < n_owned; ++r) {
    pattern.diagonal_start[r + 1] = pattern.diagonal_start[r] + diagonal_length_[r];
    pattern.off_diagonal_start[r + 1] = pattern.off_diagonal_start[r] + off_diagonal_length_[r];
  }
  pattern.diagonal_columns.resize(static_cast<size_t>(pattern.diagonal_start.back()));
  pattern.off_diagonal_columns.resize(static_cast<size_t>(pattern.off_diagonal_start.back()));
  pattern.diagonal_values.assign(pattern.diagonal_columns.size(), 0.0);
  pattern.off_diagonal_values.assign(pattern.off_diagonal_columns.size(), 0.0);
  std::vector<PetscInt> sorted, rows(4);
  std::vector<int> place;
  for (int a = 0; a < space_->n_nodes(); ++a) {
    if (degree(a) == 0) continue;  // not owned
    sorted_columns(a, sorted, place);
    for (int k = 0, n = node_rows(a, rows.data()); k < n; ++k) {
      PetscInt* diagonal = pattern.diagonal_columns.data() + pattern.diagonal_start[rows[k] - first];
      PetscInt* off = pattern.off_diagonal_columns.data() + pattern.off_diagonal_start[rows[k] - first];
      for (const PetscInt c : sorted)
        if (c >= first && c < first + n_owned)
          *diagonal++ = c - first;
        else
          *off++ = c;
    }
  }
  *A_.out() = mpi_aij_over(comm_, n_owned, n_total, std::move(pattern));
  if (n_owned % block_size() == 0 && n_total % block_size() == 0) STICTION_PETSC(MatSetBlockSize(A_, block_size()));
  STICTION_PETSC(MatSetOption(A_, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  check_distributed_pattern(diagonal_length_, off_diagonal_length_);
}

// The slots assume the layout of PETSc's MPIAIJ: per row, the diagonal part's columns
// ascending, then the off-diagonal part's, ascending in global column (its compressed
// column map is sorted). Checked for every matrix made (one pass over its columns), so that
// a PETSc that stored them otherwise fails loudly instead of assembling a wrong matrix.
void StiffnessMatrix::check_distributed_pattern(const std::vector<PetscInt>& d_nnz, const std::vector<PetscInt>& o_nnz) {
  const PetscInt* column_map;
  STICTION_PETSC(MatMPIAIJGetSeqAIJ(A_, &parts_[0], &parts_[1], &column_map));
  for (int k = 0; k < 2; ++k) {
    PetscInt n;
    const PetscInt *ia, *ja;
    PetscBool done;
    STICTION_PETSC(MatGetRowIJ(parts_[k], 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    bool ok = done && n == static_cast<PetscInt>(d_nnz.size());
    for (PetscInt r = 0; ok && r < n; ++r) {
      ok = ia[r + 1] - ia[r] == (k == 0 ? d_nnz : o_nnz)[static_cast<size_t>(r)];
      for (PetscInt e = ia[r] + 1; ok && e < ia[r + 1]; ++e)
        ok = k == 0 ? ja[e - 1] < ja[e] : column_map[ja[e - 1]] < column_map[ja[e]];
    }
    part_entries_[k] = done ? ia[n] : -1;
    STICTION_PETSC(MatRestoreRowIJ(parts_[k], 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done));
    if (!ok) throw Error("stiffness matrix: PETSc's MPIAIJ parts are not laid out as assumed", ErrorKind::Internal);
  }
}

void StiffnessMatrix::create_matrix() {
  const PetscInt n_rows = static_cast<PetscInt>(row_start_->size()) - 1;
  if (!columns_) build_columns();
  values_storage_ = std::make_shared<std::vector<PetscScalar>>();
  // Room for the constraint blocks that build_augmented_matrix merges into this array: a
  // reservation costs address space only, until a page is written.
  values_storage_->reserve(columns_->size() + columns_->size() / 16);
  values_storage_->assign(columns_->size(), 0.0);
  *A_.out() = seq_aij_over(comm_, n_rows, {row_start_, columns_, values_storage_});
  STICTION_PETSC(MatSetBlockSize(A_, block_size()));
}

CsrArrays StiffnessMatrix::take_arrays() {
  if (distributed()) throw Error("stiffness matrix: a distributed matrix has no arrays to hand over", ErrorKind::Internal);
  if (!A_) throw Error("stiffness matrix: nothing assembled to hand over", ErrorKind::Internal);
  PetscInt references;
  STICTION_PETSC(PetscObjectGetReference(reinterpret_cast<PetscObject>(A_.get()), &references));
  // Another holder of the matrix would see its values change: it keeps them, we copy.
  CsrArrays out{row_start_, columns_,
                references > 1 ? std::make_shared<std::vector<PetscScalar>>(*values_storage_) : values_storage_};
  A_.reset();
  values_storage_.reset();
  columns_.reset();  // rebuilt by the next begin_assembly: the pattern is cheap to write again
  return out;
}

void StiffnessMatrix::release() {
  A_.reset();
  values_storage_.reset();
  parts_[0] = parts_[1] = nullptr;
}

// Columns of every row of node a, in the documented layout.
void StiffnessMatrix::row_columns(int a, std::vector<PetscInt>& cols) const {
  cols.clear();
  for (int j = offsets_[a]; j < offsets_[a + 1]; ++j)
    for (int k = 0; k < dim_; ++k) cols.push_back(static_cast<PetscInt>(neighbours_[j]) * dim_ + k);
  if (mixed_[a])
    for (int j = offsets_[a]; j < offsets_[a] + vertex_degree_[a]; ++j) cols.push_back(space_->pressure_dof(neighbours_[j]));
}

void StiffnessMatrix::begin_assembly() {
  if (distributed()) {
    if (!A_)
      create_distributed_matrix();
    else
      STICTION_PETSC(MatZeroEntries(A_));  // also marks the MPIAIJ changed for its solvers
    for (int k = 0; k < 2; ++k) {
      PetscInt n;
      const PetscInt* ja;
      PetscBool done;
      STICTION_PETSC(MatGetRowIJ(parts_[k], 0, PETSC_FALSE, PETSC_FALSE, &n, &part_row_start_[k], &ja, &done));
      if (!done || part_row_start_[k][n] != part_entries_[k])
        throw Error("stiffness matrix: the distributed matrix's pattern changed since it was laid out", ErrorKind::Internal);
      STICTION_PETSC(MatSeqAIJGetArray(parts_[k], &part_values_[k]));
    }
    return;
  }
  if (!A_)
    create_matrix();
  else
    STICTION_PETSC(MatZeroEntries(A_));
  STICTION_PETSC(MatSeqAIJGetArray(A_, &values_));  // tells PETSc the values change
}

void StiffnessMatrix::add(const int* nodes, int n_nodes, int n_pressure_nodes, const double* Ke) {
  if (distributed()) return add_distributed(nodes, n_nodes, n_pressure_nodes, Ke);
  const int d = dim_, m = n_nodes * d + n_pressure_nodes;
  const std::vector<PetscInt>& row_start = *row_start_;
  for (int a = 0; a < n_nodes; ++a) {
    const int na = nodes[a], deg = degree(na);
    const int* nb_begin = &neighbours_[offsets_[na]];
    // The element rows of node a: its components, then its pressure.
    int n_rows = 0, element_row[4];
    PetscInt global_row[4];
    for (int i = 0; i < d; ++i) element_row[n_rows] = a * d + i, global_row[n_rows++] = static_cast<PetscInt>(na) * d + i;
    if (a < n_pressure_nodes) element_row[n_rows] = n_nodes * d + a, global_row[n_rows++] = space_->pressure_dof(na);
    for (int b = 0; b < n_nodes; ++b) {
      const int pos = static_cast<int>(std::lower_bound(nb_begin, nb_begin + deg, nodes[b]) - nb_begin);
      for (int r = 0; r < n_rows; ++r) {
        PetscScalar* dst = values_ + row_start[global_row[r]];
        const double* src = Ke + static_cast<size_t>(element_row[r]) * m;
        for (int k = 0; k < d; ++k) dst[d * pos + k] += src[b * d + k];
        if (b < n_pressure_nodes) dst[d * deg + pos] += src[n_nodes * d + b];
      }
    }
  }
}

void StiffnessMatrix::add_distributed(const int* nodes, int n_nodes, int n_pressure_nodes, const double* Ke) {
  const DofLayout& L = *layout_;
  const PetscInt first = L.first_owned();
  const int d = dim_, m = n_nodes * d + n_pressure_nodes;
  for (int a = 0; a < n_nodes; ++a) {
    const int na = nodes[a];
    if (!L.owns(static_cast<PetscInt>(na) * d)) continue;  // its rows are another rank's
    const int deg = degree(na);
    const int* nb_begin = &neighbours_[offsets_[na]];
    int n_rows = 0, element_row[4];
    PetscInt row[4];
    for (int i = 0; i < d; ++i) element_row[n_rows] = a * d + i, row[n_rows++] = L.global(static_cast<PetscInt>(na) * d + i) - first;
    if (a < n_pressure_nodes) element_row[n_rows] = n_nodes * d + a, row[n_rows++] = L.global(space_->pressure_dof(na)) - first;
    // The entry of row r at slot s: in the diagonal part (s >= 0) or the off-diagonal one.
    auto entry = [&](PetscInt r, int s) {
      return s >= 0 ? part_values_[0] + part_row_start_[0][r] + s : part_values_[1] + part_row_start_[1][r] + (-1 - s);
    };
    for (int b = 0; b < n_nodes; ++b) {
      const int pos = offsets_[na] + static_cast<int>(std::lower_bound(nb_begin, nb_begin + deg, nodes[b]) - nb_begin);
      const int s = column_slot_[pos];
      for (int r = 0; r < n_rows; ++r) {
        const double* src = Ke + static_cast<size_t>(element_row[r]) * m;
        // A neighbour's components are consecutive entries of one part from its slot on.
        PetscScalar* dst = entry(row[r], s);
        for (int k = 0; k < d; ++k) dst[k] += src[b * d + k];
        if (b < n_pressure_nodes) *entry(row[r], pressure_slot_[pos]) += src[n_nodes * d + b];
      }
    }
  }
}

void StiffnessMatrix::end_assembly() {
  if (!distributed()) STICTION_PETSC(MatSeqAIJRestoreArray(A_, &values_));
  for (int k = 0; distributed() && k < 2; ++k) {
    PetscInt n;
    const PetscInt* ja = nullptr;
    PetscBool done;
    STICTION_PETSC(MatSeqAIJRestoreArray(parts_[k], &part_values_[k]));
    STICTION_PETSC(MatRestoreRowIJ(parts_[k], 0, PETSC_FALSE, PETSC_FALSE, &n, &part_row_start_[k], &ja, &done));
  }
  values_ = nullptr;
  STICTION_PETSC(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY));
}

}  // namespace stiction::fem
