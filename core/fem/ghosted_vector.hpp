#pragma once
// The Newton state held per process: each process stores the unknowns it owns
// (fem::DofLayout) and, as ghosts, the others it reads (the nodes of its row cells, the
// contact surfaces), instead of the whole vector. This is PETSc's ghosted vector
// (VecCreateGhostWithArray): storage = owned entries in PETSc's order, then the ghosts;
// VecGhostUpdate copies owners' values to the ghosts (forward) or adds the ghosts' values
// into their owners (reverse). The assembly and the contact code address the storage by
// the layout's local index (the app index over the whole mesh, the part's dof over a mesh
// part) through fem::AppView, with the pattern's map. On one process the storage is the
// whole vector in app order and the view needs no map.
#include <memory>
#include <vector>

#include "common/petsc.hpp"
#include "fem/app_view.hpp"
#include "fem/dof_layout.hpp"

namespace stiction::fem {

// Which unknowns a process holds, shared by every vector of that shape.
class GhostPattern {
public:
  // The layout's owned unknowns, and as ghosts those of `needed` (local indices, in any
  // order, repeats and owned ones allowed) that another process owns.
  GhostPattern(const DofLayout& layout, const std::vector<PetscInt>& needed);

  const DofLayout& layout() const { return *layout_; }
  PetscInt n_owned() const { return layout_->n_owned(); }
  PetscInt n_ghosts() const { return static_cast<PetscInt>(ghost_local_.size()); }
  PetscInt n_stored() const { return n_owned() + n_ghosts(); }
  // Storage index of every local unknown, -1 where not stored (empty on one process: the
  // storage index is the app index).
  const std::vector<int>& storage_of_local() const { return storage_of_local_; }
  bool holds(PetscInt local) const { return storage_of_local_.empty() || storage_of_local_[local] >= 0; }

private:
  const DofLayout* layout_;
  std::vector<int> storage_of_local_;
  std::vector<PetscInt> ghost_local_;   // ascending: storage n_owned() + g holds ghost g
  std::vector<PetscInt> ghost_global_;
  friend class GhostedVector;
};

class GhostedVector {
public:
  explicit GhostedVector(std::shared_ptr<const GhostPattern> pattern);
  GhostedVector(const GhostedVector& other);
  GhostedVector& operator=(const GhostedVector& other);

  const GhostPattern& pattern() const { return *pattern_; }
  StateView view() const;
  ResidualView view();
  // The owned entries as a distributed PETSc vector over this storage (the ghosts are its
  // local form's tail); writing through it writes the storage.
  Vec vec() const;

  // Each ghost takes its owner's value.
  void update_ghosts();
  // Each owner adds its ghosts' values (the ghosts keep theirs).
  void add_ghosts_to_owners();
  // Every stored entry from an app-ordered whole vector (the same on every process).
  void assign_whole(const std::vector<double>& whole);
  // The same from a whole vector that process 0 alone need hold (collective; a shorter
  // one leaves the rest as it is).
  void assign_from_root(const std::vector<double>& whole);
  // The whole vector in app order on every process (from the owned entries).
  std::vector<double> whole() const;
  // The same on process 0 only (empty on the others).
  std::vector<double> whole_on_root() const;
  void fill(double value);

private:
  std::shared_ptr<const GhostPattern> pattern_;
  std::vector<double> storage_;
  mutable PetscVec vec_;
};

// The app unknowns of the nodes of the given cells (displacements of every node, the
// pressures of their vertices in a mixed space), ascending.
std::vector<PetscInt> unknowns_of_cells(const FieldSpace& space, const std::vector<int>& cells);
// The displacement unknowns of the nodes of the boundary facets with the given tags, ascending.
std::vector<PetscInt> unknowns_of_facets(const FieldSpace& space, const std::vector<int>& tags);

}  // namespace stiction::fem
