#include "fem/dof_layout.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

#include "common/error.hpp"

namespace stiction::fem {

DofLayout::DofLayout(MPI_Comm comm, const FieldSpace& space, const MeshPartition& partition,
                     const std::vector<int>& extra_vertices)
    : comm_(comm), rank_(partition.rank), size_(partition.size), owned_cells_(partition.owned_cells) {
  const int d = space.dim(), nn = space.n_nodes(), n_space = space.n_dofs();
  n_total_ = n_space + static_cast<PetscInt>(extra_vertices.size());
  const int nc = space.mesh().n_cells();
  if (identity()) {
    row_cells_.resize(nc);
    std::iota(row_cells_.begin(), row_cells_.end(), 0);
    return;
  }
  std::vector<int> node_owner(nn, -1), nodes(space.nodes_per_cell());
  for (int c = 0; c < nc; ++c) {
    space.cell_nodes(c, nodes.data());
    for (int n : nodes)
      if (node_owner[n] < 0) node_owner[n] = partition.cell_owner[c];
  }
  for (int c = 0; c < nc; ++c) {
    space.cell_nodes(c, nodes.data());
    if (std::any_of(nodes.begin(), nodes.end(), [&](int n) { return node_owner[n] == rank_; })) row_cells_.push_back(c);
  }
  owner_.assign(n_total_, 0);
  for (int n = 0; n < nn; ++n)
    for (int k = 0; k < d; ++k) owner_[static_cast<size_t>(n) * d + k] = node_owner[n];
  for (int v = 0; v < space.n_vertices(); ++v)
    if (space.pressure_dof(v) >= 0) owner_[space.pressure_dof(v)] = node_owner[v];
  for (size_t k = 0; k < extra_vertices.size(); ++k) owner_[n_space + k] = node_owner[extra_vertices[k]];

  // Rank by rank, app order within each rank.
  std::vector<PetscInt> count(size_, 0);
  for (int o : owner_) ++count[o];
  std::vector<PetscInt> next(size_, 0);
  for (int r = 1; r < size_; ++r) next[r] = next[r - 1] + count[r - 1];
  first_owned_ = next[rank_];
  global_.resize(n_total_);
  for (PetscInt a = 0; a < n_total_; ++a) {
    global_[a] = next[owner_[a]]++;
    if (owner_[a] == rank_) owned_local_.push_back(a);
  }
}

DofLayout::DofLayout(MPI_Comm comm, const mesh::LocalMesh& part, const FieldSpace& space, PartOwnership ownership)
    : comm_(comm), first_owned_(ownership.first_owned), owner_(std::move(ownership.owner)),
      global_(std::move(ownership.petsc)), app_(std::move(ownership.app)) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  const PetscInt n_owned = ownership.n_owned;
  MPI_Allreduce(&n_owned, &n_total_, 1, MPIU_INT, MPI_SUM, comm);
  owned_cells_.resize(static_cast<size_t>(part.n_own_cells));
  std::iota(owned_cells_.begin(), owned_cells_.end(), 0);
  std::vector<int> nodes(space.nodes_per_cell());
  for (int c = 0; c < space.mesh().n_cells(); ++c) {
    space.cell_nodes(c, nodes.data());
    if (std::any_of(nodes.begin(), nodes.end(), [&](int n) { return owner_[static_cast<size_t>(n) * space.dim()] == rank_; }))
      row_cells_.push_back(c);
  }
  if (identity()) {
    // One process's part is the whole mesh in the whole mesh's numbering.
    for (size_t i = 0; i < app_.size(); ++i)
      if (app_[i] != static_cast<PetscInt>(i) || global_[i] != app_[i])
        throw Error("dof layout: a one-process part is not numbered as the whole mesh", ErrorKind::Internal);
    return;
  }
  for (size_t i = 0; i < owner_.size(); ++i)
    if (owner_[i] == rank_) owned_local_.push_back(static_cast<PetscInt>(i));
  std::sort(owned_local_.begin(), owned_local_.end(), [&](PetscInt a, PetscInt b) { return global_[a] < global_[b]; });
  if (static_cast<PetscInt>(owned_local_.size()) != n_owned ||
      (n_owned > 0 && (global_[owned_local_.front()] != first_owned_ || global_[owned_local_.back()] != first_owned_ + n_owned - 1)))
    throw Error("dof layout: a part's owned unknowns are not its PETSc range", ErrorKind::Internal);
  std::vector<PetscInt> owned_app(owned_local_.size()), owned_petsc(owned_local_.size());
  for (size_t j = 0; j < owned_local_.size(); ++j) owned_app[j] = app_[owned_local_[j]], owned_petsc[j] = first_owned_ + static_cast<PetscInt>(j);
  STICTION_PETSC(AOCreateMemoryScalable(comm, n_owned, owned_app.data(), owned_petsc.data(), app_order_.out()));
}

void DofLayout::petsc_of_apps(std::vector<PetscInt>& apps) const {
  if (identity()) return;
  if (over_part()) {
    STICTION_PETSC(AOApplicationToPetsc(app_order_, static_cast<PetscInt>(apps.size()), apps.data()));
    return;
  }
  for (PetscInt& a : apps) a = global_[a];
}

Vec DofLayout::create_vector() const {
  Vec v;
  STICTION_PETSC(VecCreateMPI(comm_, n_owned(), n_total_, &v));
  return v;
}

void DofLayout::scatter(const std::vector<double>& values, Vec v) const {
  PetscScalar* a;
  STICTION_PETSC(VecGetArray(v, &a));
  if (identity()) std::copy(values.begin(), values.begin() + std::min<size_t>(values.size(), n_total_), a);
  for (size_t j = 0; j < owned_local_.size(); ++j)
    if (const auto k = static_cast<size_t>(app(owned_local_[j])); k < values.size()) a[j] = values[k];
  STICTION_PETSC(VecRestoreArray(v, &a));
}

void DofLayout::scatter_from_root(const std::vector<double>& values, Vec v) const {
  if (identity()) {
    scatter(values, v);
    return;
  }
  PetscOwner<VecScatter, VecScatterDestroy> to_zero;
  PetscVec whole;
  STICTION_PETSC(VecScatterCreateToZero(v, to_zero.out(), whole.out()));
  // v's present entries first, so that those the values do not reach keep theirs.
  STICTION_PETSC(VecScatterBegin(to_zero, v, whole, INSERT_VALUES, SCATTER_FORWARD));
  STICTION_PETSC(VecScatterEnd(to_zero, v, whole, INSERT_VALUES, SCATTER_FORWARD));
  std::vector<PetscInt> index(rank_ == 0 ? std::min<size_t>(values.size(), n_total_) : 0);
  std::iota(index.begin(), index.end(), 0);
  petsc_of_apps(index);
  if (rank_ == 0) {
    PetscScalar* a;
    STICTION_PETSC(VecGetArray(whole, &a));
    for (size_t k = 0; k < index.size(); ++k) a[index[k]] = values[k];
    STICTION_PETSC(VecRestoreArray(whole, &a));
  }
  STICTION_PETSC(VecScatterBegin(to_zero, whole, v, INSERT_VALUES, SCATTER_REVERSE));
  STICTION_PETSC(VecScatterEnd(to_zero, whole, v, INSERT_VALUES, SCATTER_REVERSE));
}

void DofLayout::gather(Vec v, std::vector<double>& values) const { gather_with(v, values, false); }

void DofLayout::gather_on_root(Vec v, std::vector<double>& values) const { gather_with(v, values, true); }

void DofLayout::gather_with(Vec v, std::vector<double>& values, bool root_only) const {
  const PetscScalar* a;
  if (identity()) {
    values.resize(n_total_);
    STICTION_PETSC(VecGetArrayRead(v, &a));
    std::copy(a, a + n_total_, values.begin());
    STICTION_PETSC(VecRestoreArrayRead(v, &a));
    return;
  }
  // Made for each call and freed after it: kept, the scatter and its whole-size vector
  // would stay on every process between the output steps that gather.
  PetscOwner<VecScatter, VecScatterDestroy> scatter;
  PetscVec whole;
  if (root_only) STICTION_PETSC(VecScatterCreateToZero(v, scatter.out(), whole.out()));
  else STICTION_PETSC(VecScatterCreateToAll(v, scatter.out(), whole.out()));
  STICTION_PETSC(VecScatterBegin(scatter, v, whole, INSERT_VALUES, SCATTER_FORWARD));
  STICTION_PETSC(VecScatterEnd(scatter, v, whole, INSERT_VALUES, SCATTER_FORWARD));
  values.clear();
  std::vector<PetscInt> index(root_only && rank_ != 0 ? 0 : n_total_);
  std::iota(index.begin(), index.end(), 0);
  petsc_of_apps(index);
  if (root_only && rank_ != 0) return;
  values.resize(n_total_);
  STICTION_PETSC(VecGetArrayRead(whole, &a));
  for (PetscInt k = 0; k < n_total_; ++k) values[k] = a[index[k]];
  STICTION_PETSC(VecRestoreArrayRead(whole, &a));
}

std::vector<PetscInt> DofLayout::owned_indices(PetscInt first, PetscInt last) const {
  std::vector<PetscInt> out;
  if (identity()) {
    out.resize(last - first);
    std::iota(out.begin(), out.end(), first);
    return out;
  }
  for (PetscInt l : owned_local_)
    if (l >= first && l < last) out.push_back(global(l));
  return out;
}

std::vector<PetscInt> DofLayout::block_numbering(PetscInt first, PetscInt last) const {
  std::vector<PetscInt> number(static_cast<size_t>(last - first));
  std::iota(number.begin(), number.end(), 0);
  if (identity()) return number;
  // PETSc numbers a field rank by rank, each rank's unknowns in PETSc's order
  // (owned_indices): an owned unknown's number is the count on the ranks before plus its
  // place among this rank's. The held unknowns that others own learn theirs from them.
  const std::vector<PetscInt> owned = owned_indices(first, last);
  const auto n_mine = static_cast<PetscInt>(owned.size());
  PetscInt offset = 0;
  MPI_Exscan(&n_mine, &offset, 1, MPIU_INT, MPI_SUM, comm_);
  if (rank_ == 0) offset = 0;  // MPI_Exscan leaves rank 0's result undefined
  PetscVec numbers(create_vector());
  for (PetscInt j = 0; j < n_mine; ++j)
    STICTION_PETSC(VecSetValue(numbers, owned[j], static_cast<PetscScalar>(offset + j), INSERT_VALUES));
  STICTION_PETSC(VecAssemblyBegin(numbers));
  STICTION_PETSC(VecAssemblyEnd(numbers));
  std::vector<PetscInt> held(number.size());
  for (size_t k = 0; k < held.size(); ++k) held[k] = global(first + static_cast<PetscInt>(k));
  PetscOwner<IS, ISDestroy> from;
  PetscOwner<VecScatter, VecScatterDestroy> scatter;
  PetscVec mine;
  STICTION_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(held.size()), held.data(), PETSC_USE_POINTER, from.out()));
  STICTION_PETSC(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(held.size()), mine.out()));
  STICTION_PETSC(VecScatterCreate(numbers, from, mine, nullptr, scatter.out()));
  STICTION_PETSC(VecScatterBegin(scatter, numbers, mine, INSERT_VALUES, SCATTER_FORWARD));
  STICTION_PETSC(VecScatterEnd(scatter, numbers, mine, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* a;
  STICTION_PETSC(VecGetArrayRead(mine, &a));
  for (size_t k = 0; k < number.size(); ++k) number[k] = static_cast<PetscInt>(a[k]);
  STICTION_PETSC(VecRestoreArrayRead(mine, &a));
  return number;
}

}  // namespace stiction::fem
