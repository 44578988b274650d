#include "fem/stiffness_matrix.hpp"

#include <algorithm>

#include "common/error.hpp"

namespace stiction::fem {

StiffnessMatrix::StiffnessMatrix(MPI_Comm comm, const DisplacementSpace& space) : dim_(space.dim()) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size != 1) throw Error("stiction runs on one MPI rank for now (the mesh is not distributed yet)");
  const int nn = space.n_nodes(), npc = space.nodes_per_cell(), nc = space.mesh().n_cells(), d = dim_;

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
  }

  const PetscInt n = space.n_dofs();
  std::vector<PetscInt> nnz(n);
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < d; ++i) nnz[static_cast<size_t>(a) * d + i] = d * degree(a);
  STICTION_PETSC(MatCreate(comm, A_.out()));
  STICTION_PETSC(MatSetSizes(A_, n, n, n, n));
  STICTION_PETSC(MatSetType(A_, MATAIJ));
  STICTION_PETSC(MatSetBlockSize(A_, d));
  STICTION_PETSC(MatSeqAIJSetPreallocation(A_, 0, nnz.data()));
  STICTION_PETSC(MatMPIAIJSetPreallocation(A_, 0, nnz.data(), 0, nullptr));
  std::vector<PetscInt>().swap(nnz);
  // Fix the pattern by inserting explicit zeros, one node's rows at a time.
  std::vector<PetscInt> rows(d), cols;
  std::vector<PetscScalar> zeros;
  for (int a = 0; a < nn; ++a) {
    cols.clear();
    for (int j = offsets_[a]; j < offsets_[a + 1]; ++j)
      for (int k = 0; k < d; ++k) cols.push_back(static_cast<PetscInt>(neighbours_[j]) * d + k);
    for (int i = 0; i < d; ++i) rows[i] = static_cast<PetscInt>(a) * d + i;
    zeros.assign(rows.size() * cols.size(), 0.0);
    STICTION_PETSC(MatSetValues(A_, d, rows.data(), static_cast<PetscInt>(cols.size()), cols.data(), zeros.data(),
                                INSERT_VALUES));
  }
  STICTION_PETSC(MatAssemblyBegin(A_, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(A_, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatSetOption(A_, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
  PetscBool seq = PETSC_FALSE;
  STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(A_.get()), MATSEQAIJ, &seq));
  direct_ = seq && layout_matches_petsc();
}

// Row a*d+i of the direct layout starts at d*d*offsets[a] + i*d*degree(a).
bool StiffnessMatrix::layout_matches_petsc() const {
  const PetscInt* ia;
  const PetscInt* ja;
  PetscInt n;
  PetscBool done;
  if (MatGetRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done) || !done) return false;
  bool ok = true;
  const int d = dim_;
  for (int a = 0; ok && a < static_cast<int>(offsets_.size()) - 1; ++a)
    for (int i = 0; i < d; ++i) {
      const PetscInt start = static_cast<PetscInt>(d) * d * offsets_[a] + static_cast<PetscInt>(i) * d * degree(a);
      if (ia[a * d + i] != start || ja[start] != static_cast<PetscInt>(neighbours_[offsets_[a]]) * d) ok = false;
    }
  MatRestoreRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done);
  return ok;
}

void StiffnessMatrix::begin_assembly() {
  STICTION_PETSC(MatZeroEntries(A_));
  if (direct_) STICTION_PETSC(MatSeqAIJGetArray(A_, &values_));
}

void StiffnessMatrix::add(const int* nodes, int n_nodes, const double* Ke) {
  const int d = dim_, nd = n_nodes * d;
  if (!direct_) {
    PetscInt idx[64];
    for (int a = 0; a < n_nodes; ++a)
      for (int i = 0; i < d; ++i) idx[a * d + i] = static_cast<PetscInt>(nodes[a]) * d + i;
    STICTION_PETSC(MatSetValues(A_, nd, idx, nd, idx, Ke, ADD_VALUES));
    return;
  }
  for (int a = 0; a < n_nodes; ++a) {
    const int na = nodes[a], deg = degree(na);
    const int* nb_begin = &neighbours_[offsets_[na]];
    PetscScalar* base = values_ + static_cast<size_t>(d) * d * offsets_[na];
    for (int b = 0; b < n_nodes; ++b) {
      const int pos = static_cast<int>(std::lower_bound(nb_begin, nb_begin + deg, nodes[b]) - nb_begin);
      for (int i = 0; i < d; ++i) {
        PetscScalar* dst = base + static_cast<size_t>(i) * d * deg + static_cast<size_t>(d) * pos;
        const double* src = Ke + static_cast<size_t>(a * d + i) * nd + b * d;
        for (int k = 0; k < d; ++k) dst[k] += src[k];
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
