#pragma once
// Which process owns each unknown of a mesh part's space, and PETSc's index of each, as
// fem::DofLayout gives them on the whole mesh: a node belongs to the owner of the lowest-id
// cell holding it and a pressure to its vertex's owner; PETSc numbers the unknowns process
// by process, in app order (fem::PartNumbering's whole-space numbers) within each. A process
// numbers the unknowns it owns and learns the others' indices from their owners through
// PETSc's scalable application ordering (AOCreateMemoryScalable), so nothing of the size of
// the whole system is held.
#include <vector>

#include <petscao.h>

#include "fem/part_numbering.hpp"

namespace stiction::fem {

struct PartOwnership {
  // Per dof of the part's space (its local dof order: node * dim + component, then the
  // pressures), then per extra unknown: the whole-space (app) index, PETSc's index, and the
  // owning process (-1 for the nodes of ghost cells only, whose owner the part cannot tell:
  // another process's).
  std::vector<PetscInt> app, petsc;
  std::vector<int> owner;
  PetscInt n_owned = 0, first_owned = 0;
};

// Collective. extra_vertices: one extra unknown per entry (a contact multiplier of the slave
// node at that part vertex, the same list on every process), held by every process after
// the space's dofs, with app indices after the whole space's and its vertex's owner as
// owner, as fem::DofLayout numbers extra unknowns over the whole mesh.
PartOwnership own_part_unknowns(MPI_Comm comm, const mesh::LocalMesh& part, const FieldSpace& space,
                                const PartNumbering& numbering, const std::vector<int>& extra_vertices = {});

}  // namespace stiction::fem
