#include "fem/ghosted_vector.hpp"

#include <algorithm>

namespace stiction::fem {

GhostPattern::GhostPattern(const DofLayout& layout, const std::vector<PetscInt>& needed) : layout_(&layout) {
  if (layout.identity()) return;
  for (PetscInt l : needed)
    if (!layout.owns(l)) ghost_local_.push_back(l);
  std::sort(ghost_local_.begin(), ghost_local_.end());
  ghost_local_.erase(std::unique(ghost_local_.begin(), ghost_local_.end()), ghost_local_.end());
  storage_of_local_.assign(static_cast<size_t>(layout.n_held()), -1);
  // The owned entries in PETSc's order: storage j is global index first_owned() + j.
  for (PetscInt l = 0; l < layout.n_held(); ++l)
    if (layout.owns(l)) storage_of_local_[l] = static_cast<int>(layout.global(l) - layout.first_owned());
  const PetscInt n_owned = layout.n_owned();
  ghost_global_.reserve(ghost_local_.size());
  for (size_t g = 0; g < ghost_local_.size(); ++g) {
    storage_of_local_[ghost_local_[g]] = static_cast<int>(n_owned + static_cast<PetscInt>(g));
    ghost_global_.push_back(layout.global(ghost_local_[g]));
  }
}

GhostedVector::GhostedVector(std::shared_ptr<const GhostPattern> pattern)
    : pattern_(std::move(pattern)), storage_(static_cast<size_t>(pattern_->n_stored()), 0.0) {}

GhostedVector::GhostedVector(const GhostedVector& other) : pattern_(other.pattern_), storage_(other.storage_) {}

GhostedVector& GhostedVector::operator=(const GhostedVector& other) {
  if (this == &other) return *this;
  if (pattern_ == other.pattern_) {
    std::copy(other.storage_.begin(), other.storage_.end(), storage_.begin());  // a Vec wraps storage_
    return *this;
  }
  pattern_ = other.pattern_;
  storage_ = other.storage_;
  vec_.reset();
  return *this;
}

// Made on first use: a ghosted Vec carries its own ghost scatter (on several processes a
// tenth of the vector's size again), and most of the Newton driver's vectors are never
// scattered.
Vec GhostedVector::vec() const {
  if (vec_) return vec_;
  const DofLayout& layout = pattern_->layout();
  const auto& ghosts = pattern_->ghost_global_;
  STICTION_PETSC(VecCreateGhostWithArray(layout.comm(), layout.n_owned(), layout.n_total(),
                                         static_cast<PetscInt>(ghosts.size()), ghosts.data(),
                                         const_cast<double*>(storage_.data()), vec_.out()));
  return vec_;
}

StateView GhostedVector::view() const {
  const auto& map = pattern_->storage_of_local();
  if (map.empty()) return storage_;
  return {storage_.data(), storage_.size(), map.data(), map.size()};
}

ResidualView GhostedVector::view() {
  const auto& map = pattern_->storage_of_local();
  if (map.empty()) return storage_;
  return {storage_.data(), storage_.size(), map.data(), map.size()};
}

void GhostedVector::update_ghosts() {
  if (pattern_->layout().identity()) return;
  STICTION_PETSC(VecGhostUpdateBegin(vec(), INSERT_VALUES, SCATTER_FORWARD));
  STICTION_PETSC(VecGhostUpdateEnd(vec(), INSERT_VALUES, SCATTER_FORWARD));
}

void GhostedVector::add_ghosts_to_owners() {
  if (pattern_->layout().identity()) return;
  STICTION_PETSC(VecGhostUpdateBegin(vec(), ADD_VALUES, SCATTER_REVERSE));
  STICTION_PETSC(VecGhostUpdateEnd(vec(), ADD_VALUES, SCATTER_REVERSE));
}

void GhostedVector::assign_whole(const std::vector<double>& whole) {
  const auto& map = pattern_->storage_of_local();
  if (map.empty()) {
    std::copy(whole.begin(), whole.begin() + std::min(whole.size(), storage_.size()), storage_.begin());
    return;
  }
  const DofLayout& layout = pattern_->layout();
  for (size_t l = 0; l < map.size(); ++l)
    if (const auto a = static_cast<size_t>(layout.app(static_cast<PetscInt>(l))); map[l] >= 0 && a < whole.size())
      storage_[static_cast<size_t>(map[l])] = whole[a];
}

void GhostedVector::assign_from_root(const std::vector<double>& whole) {
  if (pattern_->layout().identity()) {
    assign_whole(whole);
    return;
  }
  pattern_->layout().scatter_from_root(whole, vec());
  update_ghosts();
}

std::vector<double> GhostedVector::whole() const {
  std::vector<double> out;
  pattern_->layout().gather(vec(), out);
  return out;
}

std::vector<double> GhostedVector::whole_on_root() const {
  std::vector<double> out;
  pattern_->layout().gather_on_root(vec(), out);
  return out;
}

void GhostedVector::fill(double value) { std::fill(storage_.begin(), storage_.end(), value); }

std::vector<PetscInt> unknowns_of_cells(const FieldSpace& space, const std::vector<int>& cells) {
  const int d = space.dim();
  std::vector<int> nodes(space.nodes_per_cell());
  std::vector<char> held(static_cast<size_t>(space.n_dofs()), 0);
  for (int c : cells) {
    space.cell_nodes(c, nodes.data());
    for (int n : nodes) {
      for (int k = 0; k < d; ++k) held[static_cast<size_t>(n) * d + k] = 1;
      if (space.is_vertex_node(n) && space.pressure_dof(n) >= 0) held[space.pressure_dof(n)] = 1;
    }
  }
  std::vector<PetscInt> out;
  for (size_t a = 0; a < held.size(); ++a)
    if (held[a]) out.push_back(static_cast<PetscInt>(a));
  return out;
}

std::vector<PetscInt> unknowns_of_facets(const FieldSpace& space, const std::vector<int>& tags) {
  const int d = space.dim();
  const mesh::Mesh& mesh = space.mesh();
  std::vector<int> nodes(space.nodes_per_facet());
  std::vector<PetscInt> out;
  for (int f = 0; f < mesh.n_facets(); ++f) {
    if (std::find(tags.begin(), tags.end(), mesh.facet_tags[f]) == tags.end()) continue;
    space.facet_nodes(f, nodes.data());
    for (int n : nodes)
      for (int k = 0; k < d; ++k) out.push_back(static_cast<PetscInt>(n) * d + k);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace stiction::fem
