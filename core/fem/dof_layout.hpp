#pragma once
// The Newton system's numbering across MPI ranks. Its unknowns in stiction's own order
// (the "app" order: displacement node by node, then pressures, then multipliers) are the
// index by which, over the whole mesh, the assembly and the contact code address the state
// (fem::AppView, over each rank's owned and ghost storage: fem::GhostedVector; over a mesh
// part, see below); PETSc's distributed matrix and
// vectors number them rank by rank instead, each rank's unknowns a contiguous range, in app
// order within the rank. So on one rank the two numberings are the same, and nothing is
// permuted.
//
// Ownership: a node belongs to the rank of the first cell (lowest index) that holds it,
// its pressure and its multipliers follow it (the multiplier rows stay on the rank that
// owns the slave node). The cells whose element matrices reach a rank's rows (row_cells)
// are its own cells and the layer around them that holds one of its nodes.
//
// A layout addresses the unknowns a rank holds by their local index: the index its own
// FieldSpace gives them (dof, then the extra unknowns). Over the whole mesh, held on every
// rank, the local index is the app index. Over a mesh part (mesh::LocalMesh, whose space
// numbers the part's dofs locally) it is the part's dof, app(local) gives the whole
// space's index, and PETSc's index of an app index the part does not hold is asked of its
// owner through PETSc's scalable application ordering (AOCreateMemoryScalable), so that no
// per-unknown array of the whole system's size is kept.
#include <vector>

#include <petscao.h>

#include "common/petsc.hpp"
#include "fem/field_space.hpp"
#include "fem/mesh_partition.hpp"
#include "fem/part_ownership.hpp"

namespace stiction::fem {

class DofLayout {
public:
  // The space's dofs followed by one extra unknown per entry of extra_vertices (a
  // multiplier of the slave node at that mesh vertex).
  DofLayout(MPI_Comm comm, const FieldSpace& space, const MeshPartition& partition,
            const std::vector<int>& extra_vertices);
  // Over a mesh part: space is the part's (part.mesh), ownership its unknowns' owners and
  // indices (fem::own_part_unknowns; the layout keeps them, so pass it moved when it is not
  // needed afterwards), the extra unknowns (multipliers) among them after the space's dofs.
  // Collective.
  DofLayout(MPI_Comm comm, const mesh::LocalMesh& part, const FieldSpace& space, PartOwnership ownership);

  MPI_Comm comm() const { return comm_; }
  bool identity() const { return size_ == 1; }
  bool over_part() const { return !app_.empty(); }
  // This rank's cells, ascending, in the space's numbering (every cell on one rank).
  const std::vector<int>& owned_cells() const { return owned_cells_; }
  // The cells holding at least one node this rank owns, ascending (every cell on one rank):
  // the tangent's owned rows are complete from these cells' element matrices alone.
  const std::vector<int>& row_cells() const { return row_cells_; }
  PetscInt n_total() const { return n_total_; }
  // The unknowns this rank's space addresses (local indices [0, n_held)): every one over the
  // whole mesh, the part's over a part.
  PetscInt n_held() const { return over_part() ? static_cast<PetscInt>(app_.size()) : n_total_; }
  PetscInt n_owned() const { return identity() ? n_total_ : static_cast<PetscInt>(owned_local_.size()); }
  PetscInt first_owned() const { return first_owned_; }
  // PETSc's index of a held unknown, whether this rank owns it, its owner (-1 over a part
  // where the part does not hold the node's whole star) and its app index.
  PetscInt global(PetscInt local) const { return identity() ? local : global_[local]; }
  bool owns(PetscInt local) const { return identity() || owner_[local] == rank_; }
  int owner(PetscInt local) const { return identity() ? 0 : owner_[local]; }
  PetscInt app(PetscInt local) const { return over_part() ? app_[local] : local; }

  // The local index of the owned unknown at position j of this rank's range (PETSc index
  // first_owned() + j).
  PetscInt local_of_owned(PetscInt j) const { return identity() ? j : owned_local_[j]; }
  // A vector of the whole system's size with this layout's ownership.
  Vec create_vector() const;
  // The owned entries of v from app-ordered values (values[k] is unknown k; values may be
  // shorter than the system: the rest of v is left as it is).
  void scatter(const std::vector<double>& values, Vec v) const;
  // scatter's counterpart from rank 0: the owned entries of v from app-ordered values that
  // rank 0 alone holds (values on the other ranks are not read; shorter values leave the
  // rest of v as it is).
  void scatter_from_root(const std::vector<double>& values, Vec v) const;
  // Every entry of v on every rank, in app order.
  void gather(Vec v, std::vector<double>& values) const;
  // Every entry of v in app order on rank 0; values is left empty on the other ranks (what
  // one writer needs, without a whole-size copy on every process).
  void gather_on_root(Vec v, std::vector<double>& values) const;
  // The owned PETSc indices of local unknowns [first, last), ascending. The space's field
  // blocks are local ranges (FieldSpace::linear_block() etc.): over a part, the part's
  // vertex, edge and pressure dofs are the whole space's of the same blocks.
  std::vector<PetscInt> owned_indices(PetscInt first, PetscInt last) const;
  // The numbering of a field block that PETSc gives it as a field (MatCreateSubMatrix,
  // VecGetSubVector over owned_indices): process by process, in PETSc's order within each.
  // Entry k is local unknown first + k's index in it; on one rank, k. Collective.
  std::vector<PetscInt> block_numbering(PetscInt first, PetscInt last) const;

private:
  void gather_with(Vec v, std::vector<double>& values, bool root_only) const;
  // PETSc's indices of the app unknowns in apps, in place (collective over a part).
  void petsc_of_apps(std::vector<PetscInt>& apps) const;

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  PetscInt n_total_ = 0, first_owned_ = 0;
  std::vector<int> owner_;            // per held unknown (empty on one rank)
  std::vector<PetscInt> global_;      // per held unknown (empty on one rank)
  std::vector<PetscInt> app_;         // per held unknown over a part (empty over the whole mesh)
  std::vector<PetscInt> owned_local_; // local index of each owned unknown, in PETSc order (several ranks)
  std::vector<int> owned_cells_, row_cells_;
  PetscOwner<AO, AODestroy> app_order_;  // over a part on several ranks
};

}  // namespace stiction::fem
