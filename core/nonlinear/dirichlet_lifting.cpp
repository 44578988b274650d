#include "nonlinear/dirichlet_lifting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace stiction::nonlinear {

DirichletLifting::DirichletLifting(const ElasticityProblem& problem) : problem_(problem) {
  const fem::FieldSpace& space = *problem.space;
  const int d = space.dim();
  is_constrained_.assign(space.n_dofs(), 0);
  std::vector<int> nodes(space.nodes_per_facet());
  for (const auto& bc : problem.dirichlet) {
    std::vector<int> bc_nodes;
    for (int f = 0; f < space.mesh().n_facets(); ++f) {
      if (space.mesh().facet_tags[f] != bc.facet_tag) continue;
      space.facet_nodes(f, nodes.data());
      bc_nodes.insert(bc_nodes.end(), nodes.begin(), nodes.end());
    }
    std::sort(bc_nodes.begin(), bc_nodes.end());
    bc_nodes.erase(std::unique(bc_nodes.begin(), bc_nodes.end()), bc_nodes.end());
    if (bc_nodes.empty()) throw Error(fmt::format("Dirichlet condition '{}': its boundary has no facets", bc.name));
    for (int n : bc_nodes)
      for (int c : bc.components) is_constrained_[static_cast<size_t>(n) * d + c] = 1;
    bc_nodes_.push_back(std::move(bc_nodes));
  }
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

bool DirichletLifting::pending(fem::StateView u) const {
  for (size_t k = 0; k < constrained_.size(); ++k)
    if (u[constrained_[k]] != target_[k]) return true;
  return false;
}

void DirichletLifting::impose(std::vector<double>& u) const {
  for (size_t k = 0; k < constrained_.size(); ++k) u[constrained_[k]] = target_[k];
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

double DirichletLifting::free_norm(const std::vector<double>& r) const {
  double s = 0;
  for (size_t i = 0; i < r.size(); ++i)
    if (!is_constrained_[i]) s += r[i] * r[i];
  return std::sqrt(s);
}

double DirichletLifting::free_norm(const fem::DofLayout& layout, Vec v) const {
  std::vector<double> b;
  layout.gather(v, b);
  b.resize(is_constrained_.size());
  return free_norm(b);
}

std::map<std::string, std::array<double, 3>> DirichletLifting::reactions(const std::vector<double>& r) const {
  const fem::FieldSpace& space = *problem_.space;
  const int d = space.dim();
  std::map<std::string, std::array<double, 3>> out;
  for (size_t b = 0; b < problem_.dirichlet.size(); ++b) {
    std::array<double, 3> f{0, 0, 0};
    for (int n : bc_nodes_[b])
      for (int k = 0; k < d; ++k) f[k] += space.unit_weight(n) * r[static_cast<size_t>(n) * d + k];
    out[problem_.dirichlet[b].name] = f;
  }
  return out;
}

}  // namespace stiction::nonlinear
