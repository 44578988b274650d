#include "nonlinear/dirichlet_lifting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace stiction::nonlinear {

DirichletLifting::DirichletLifting(MPI_Comm comm, const ElasticityProblem& problem) : problem_(problem) {
  const fem::FieldSpace& space = *problem.space;
  const int d = space.dim();
  is_constrained_.assign(space.n_dofs(), 0);
  std::vector<int> nodes(space.nodes_per_facet());
  std::vector<int> n_facets;  // per condition: a mesh part may hold none of a boundary's facets
  for (const auto& bc : problem.dirichlet) {
    std::vector<int> bc_nodes;
    n_facets.push_back(0);
    for (int f = 0; f < space.mesh().n_facets(); ++f) {
      if (space.mesh().facet_tags[f] != bc.facet_tag) continue;
      space.facet_nodes(f, nodes.data());
      bc_nodes.insert(bc_nodes.end(), nodes.begin(), nodes.end());
      ++n_facets.back();
    }
    std::sort(bc_nodes.begin(), bc_nodes.end());
    bc_nodes.erase(std::unique(bc_nodes.begin(), bc_nodes.end()), bc_nodes.end());
    for (int n : bc_nodes)
      for (int c : bc.components) is_constrained_[static_cast<size_t>(n) * d + c] = 1;
    bc_nodes_.push_back(std::move(bc_nodes));
  }
  MPI_Allreduce(MPI_IN_PLACE, n_facets.data(), static_cast<int>(n_facets.size()), MPI_INT, MPI_SUM, comm);
  for (size_t b = 0; b < n_facets.size(); ++b)
    if (n_facets[b] == 0) throw Error(fmt::format("Dirichlet condition '{}': its boundary has no facets", problem.dirichlet[b].name));
  for (int i = 0; i < space.n_dofs(); ++i)
    if (is_constrained_[i]) constrained_.push_back(i);
}

void DirichletLifting::set_targets(double t) {
  const fem::FieldSpace& space = *problem_.space;
  const int d = space.dim();
  std::vector<double> full_target(space.n_dofs(), 0.0);
  for (size_t b = 0; b < problem_.dirichlet.size(); ++b) {
    const auto& bc = problem_.dirichlet[b];
    double val[3];
    for (int n : bc_nodes_[b]) {
      space.interpolate_node([&](const double* X, double* out) { bc.value(X, t, out); }, n, val);
      for (int c : bc.components) full_target[static_cast<size_t>(n) * d + c] = val[c];
    }
  }
  target_.resize(constrained_.size());
  for (size_t k = 0; k < constrained_.size(); ++k) target_[k] = full_target[constrained_[k]];
}

bool DirichletLifting::pending(const fem::DofLayout& layout, fem::StateView u) const {
  int mine = 0;
  for (size_t k = 0; k < constrained_.size() && !mine; ++k)
    if (layout.owns(constrained_[k]) && u[constrained_[k]] != target_[k]) mine = 1;
  if (layout.identity()) return mine;
  int any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, layout.comm());
  return any;
}

void DirichletLifting::impose(fem::ResidualView u) const {
  for (size_t k = 0; k < constrained_.size(); ++k)
    if (u.holds(constrained_[k])) u[constrained_[k]] = target_[k];
}

void DirichletLifting::apply(const fem::DofLayout& layout, Mat A, Vec rhs, fem::StateView u,
                             bool lift) const {
  PetscVec x;
  STICTION_PETSC(VecDuplicate(rhs, x.out()));
  STICTION_PETSC(VecZeroEntries(x));
  std::vector<PetscInt> rows;
  rows.reserve(constrained_.size());
  for (size_t k = 0; k < constrained_.size(); ++k) {
    if (!layout.owns(constrained_[k])) continue;
    rows.push_back(layout.global(constrained_[k]));
    if (lift) STICTION_PETSC(VecSetValue(x, rows.back(), target_[k] - u[constrained_[k]], INSERT_VALUES));
  }
  STICTION_PETSC(VecAssemblyBegin(x));
  STICTION_PETSC(VecAssemblyEnd(x));
  STICTION_PETSC(MatZeroRowsColumns(A, static_cast<PetscInt>(rows.size()), rows.data(), 1.0, x, rhs));
}

double DirichletLifting::free_norm(const fem::DofLayout& layout, fem::StateView r) const {
  double s = 0;
  const size_t n = is_constrained_.size();
  if (layout.identity()) {
    for (size_t i = 0; i < n; ++i)
      if (!is_constrained_[i]) s += r[i] * r[i];
    return std::sqrt(s);
  }
  for (PetscInt j = 0; j < layout.n_owned(); ++j) {
    const auto a = static_cast<size_t>(layout.local_of_owned(j));
    if (a < n && !is_constrained_[a]) s += r[a] * r[a];
  }
  return std::sqrt(fem::sum_over_ranks(layout.comm(), s));
}

double DirichletLifting::free_norm(const fem::DofLayout& layout, Vec v) const {
  const PetscScalar* a;
  STICTION_PETSC(VecGetArrayRead(v, &a));
  PetscInt n_local;
  STICTION_PETSC(VecGetLocalSize(v, &n_local));
  double s = 0;
  for (PetscInt j = 0; j < n_local; ++j) {
    const auto app = static_cast<size_t>(layout.local_of_owned(j));
    if (app < is_constrained_.size() && !is_constrained_[app]) s += a[j] * a[j];
  }
  STICTION_PETSC(VecRestoreArrayRead(v, &a));
  return std::sqrt(layout.identity() ? s : fem::sum_over_ranks(layout.comm(), s));
}

std::map<std::string, std::array<double, 3>> DirichletLifting::reactions(const fem::DofLayout& layout,
                                                                        fem::StateView r) const {
  const fem::FieldSpace& space = *problem_.space;
  const int d = space.dim();
  std::map<std::string, std::array<double, 3>> out;
  for (size_t b = 0; b < problem_.dirichlet.size(); ++b) {
    std::vector<double> f(3, 0.0);
    for (int n : bc_nodes_[b])
      for (int k = 0; k < d; ++k) {
        const size_t dof = static_cast<size_t>(n) * d + k;
        if (layout.owns(static_cast<PetscInt>(dof))) f[k] += space.unit_weight(n) * r[dof];
      }
    if (!layout.identity()) fem::sum_over_ranks(layout.comm(), f);
    out[problem_.dirichlet[b].name] = {f[0], f[1], f[2]};
  }
  return out;
}

}  // namespace stiction::nonlinear
