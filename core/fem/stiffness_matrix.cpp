#include "fem/stiffness_matrix.hpp"

#include <algorithm>

#include "common/error.hpp"

namespace stiction::fem {

StiffnessMatrix::StiffnessMatrix(MPI_Comm comm, const FieldSpace& space) : space_(&space), dim_(space.dim()) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size != 1) throw Error("stiction runs on one MPI rank for now (the mesh is not distributed yet)");
  const int nn = space.n_nodes(), npc = space.nodes_per_cell(), nc = space.mesh().n_cells(), d = dim_;
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

  // Row lengths in global row order: displacement rows, then pressure rows.
  const PetscInt n_rows = space.n_dofs();
  std::vector<PetscInt> nnz(n_rows);
  for (int a = 0; a < nn; ++a) {
    const PetscInt len = static_cast<PetscInt>(d) * degree(a) + (mixed_[a] ? vertex_degree_[a] : 0);
    for (int i = 0; i < d; ++i) nnz[static_cast<size_t>(a) * d + i] = len;
    if (a < nv && space.pressure_dof(a) >= 0) nnz[space.pressure_dof(a)] = len;
  }
  row_start_.assign(n_rows + 1, 0);
  for (PetscInt r = 0; r < n_rows; ++r) row_start_[r + 1] = row_start_[r] + nnz[r];

  STICTION_PETSC(MatCreate(comm, A_.out()));
  STICTION_PETSC(MatSetSizes(A_, n_rows, n_rows, n_rows, n_rows));
  STICTION_PETSC(MatSetType(A_, MATAIJ));
  STICTION_PETSC(MatSetBlockSize(A_, space.has_pressure() ? 1 : d));
  STICTION_PETSC(MatSeqAIJSetPreallocation(A_, 0, nnz.data()));
  STICTION_PETSC(MatMPIAIJSetPreallocation(A_, 0, nnz.data(), 0, nullptr));
  std::vector<PetscInt>().swap(nnz);
  // Fix the pattern by inserting explicit zeros, one node's rows at a time.
  std::vector<PetscInt> rows;
  std::vector<PetscScalar> zeros;
  for (int a = 0; a < nn; ++a) {
    const std::vector<PetscInt> cols = row_columns(a);
    rows.clear();
    for (int i = 0; i < d; ++i) rows.push_back(static_cast<PetscInt>(a) * d + i);
    if (a < nv && space.pressure_dof(a) >= 0) rows.push_back(space.pressure_dof(a));
    zeros.assign(rows.size() * cols.size(), 0.0);
    STICTION_PETSC(MatSetValues(A_, static_cast<PetscInt>(rows.size()), rows.data(), static_cast<PetscInt>(cols.size()),
                                cols.data(), zeros.data(), INSERT_VALUES));
  }
  STICTION_PETSC(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatSetOption(A_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscBool seq = PETSC_FALSE;
  STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A_.get()), MATSEQAIJ, &seq));
  direct_ = seq && layout_matches_petsc();
}

// Columns of every row of node a, in the documented layout.
std::vector<PetscInt> StiffnessMatrix::row_columns(int a) const {
  std::vector<PetscInt> cols;
  for (int j = offsets_[a]; j < offsets_[a + 1]; ++j)
    for (int k = 0; k < dim_; ++k) cols.push_back(static_cast<PetscInt>(neighbours_[j]) * dim_ + k);
  if (mixed_[a])
    for (int j = offsets_[a]; j < offsets_[a] + vertex_degree_[a]; ++j) cols.push_back(space_->pressure_dof(neighbours_[j]));
  return cols;
}

bool StiffnessMatrix::layout_matches_petsc() const {
  const PetscInt* ia;
  const PetscInt* ja;
  PetscInt n;
  PetscBool done;
  if (MatGetRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done) || !done) return false;
  bool ok = n + 1 == static_cast<PetscInt>(row_start_.size());
  for (PetscInt r = 0; ok && r <= n; ++r) ok = ia[r] == row_start_[r];
  MatRestoreRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
  return ok;
}

void StiffnessMatrix::begin_assembly() {
  STICTION_PETSC(MatZeroEntries(A_));
  if (direct_) STICTION_PETSC(MatSeqAIJGetArray(A_, &values_));
}

void StiffnessMatrix::add(const int* nodes, int n_nodes, int n_pressure_nodes, const double* Ke) {
  const int d = dim_, m = n_nodes * d + n_pressure_nodes;
  if (!direct_) {
    PetscInt idx[64];
    for (int a = 0; a < n_nodes; ++a)
      for (int i = 0; i < d; ++i) idx[a * d + i] = static_cast<PetscInt>(nodes[a]) * d + i;
    for (int a = 0; a < n_pressure_nodes; ++a) idx[n_nodes * d + a] = space_->pressure_dof(nodes[a]);
    STICTION_PETSC(MatSetValues(A_, m, idx, m, idx, Ke, ADD_VALUES));
    return;
  }
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
        PetscScalar* dst = values_ + row_start_[global_row[r]];
        const double* src = Ke + static_cast<size_t>(element_row[r]) * m;
        for (int k = 0; k < d; ++k) dst[d * pos + k] += src[b * d + k];
        if (b < n_pressure_nodes) dst[d * deg + pos] += src[n_nodes * d + b];
      }
    }
  }
}

void StiffnessMatrix::end_assembly() {
  if (direct_) {
    STICTION_PETSC(MatSeqAIJRestoreArray(A_, &values_));
    values_ = nullptr;
  }
  STICTION_PETSC(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY));
}

}  // namespace stiction::fem
