#pragma once
// Derivative columns of a slave facet's vertex nodes summed over the facet's contact points
// before they reach the nodes' maps (surface_contact.cpp).
#include <array>
#include <map>
#include <vector>

#include <petscsys.h>

#include "contact/contact_pair.hpp"

namespace stiction::contact {

// columns[dof] += v, starting from zero (Eigen's fixed-size vectors are not zero-initialised).
template <class V>
void add_column(std::map<PetscInt, V>& columns, PetscInt dof, const V& v) {
  columns.try_emplace(dof, V::Zero()).first->second += v;
}

// The columns d G_i / du and d S_i / du of one slave facet's vertex nodes i (k = 0 .. D - 1),
// summed over the facet's points before they reach the nodes' maps. The points of a facet
// share their columns (the facet's unknowns and those of the few master facets they cross),
// so one map insertion per column and node replaces one per point and node. Columns find
// their slot through a table indexed by unknown, reset at each flush.
class FacetColumns {
public:
  explicit FacetColumns(int n_dofs) : slot_(static_cast<size_t>(n_dofs), -1) {}

  void add(int k, PetscInt dof, const Vec3& dG, const Vec3& dS) {
    int& slot = slot_[static_cast<size_t>(dof)];
    if (slot < 0) {
      slot = static_cast<int>(dofs_.size());
      dofs_.push_back(dof);
      sums_.emplace_back();
      for (auto& v : sums_.back()) v.setZero();
    }
    sums_[slot][2 * k] += dG, sums_[slot][2 * k + 1] += dS;
  }

  // Adds node k's sums into node_k(k)'s maps (null: not derived) and empties the table.
  template <class NodeOf>
  void flush(int n_nodes, const NodeOf& node_k) {
    for (int k = 0; k < n_nodes; ++k) {
      NodeKinematics* node = node_k(k);
      if (!node) continue;
      for (size_t j = 0; j < dofs_.size(); ++j) {
        const Vec3 &dG = sums_[j][2 * k], &dS = sums_[j][2 * k + 1];
        if (dG.isZero(0) && dS.isZero(0)) continue;  // the column of another vertex only
        add_column(node->dG, dofs_[j], dG);
        add_column(node->dS, dofs_[j], dS);
      }
    }
    for (const PetscInt dof : dofs_) slot_[static_cast<size_t>(dof)] = -1;
    dofs_.clear(), sums_.clear();
  }

private:
  std::vector<int> slot_;
  std::vector<PetscInt> dofs_;
  std::vector<std::array<Vec3, 6>> sums_;  // per column: (dG, dS) of vertex 0, 1, 2
};

}  // namespace stiction::contact
