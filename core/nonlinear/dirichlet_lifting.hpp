#pragma once
// Dirichlet conditions by lifting: which dofs are prescribed, their values at the end of an
// increment, and the prescribed increment written into the increment's first linear system.
// Constrained rows and columns become identity (MatZeroRowsColumns keeps the matrix
// symmetric); the right side takes the prescribed increment on them and, through the
// removed columns, its effect on the free rows. So the predictor is the linearised response
// to the new boundary values instead of a jump that can invert boundary cells.
//
// Norms and reactions read only the free rows (free_norm) or only the prescribed nodes
// (reactions): the residual on a prescribed dof is the reaction there, not an error.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "common/petsc.hpp"
#include "fem/app_view.hpp"
#include "fem/dof_layout.hpp"
#include "nonlinear/problem.hpp"

namespace stiction::nonlinear {

class DirichletLifting {
public:
  // Collective; throws when a condition's boundary has no facets on any process.
  DirichletLifting(MPI_Comm comm, const ElasticityProblem& problem);

  // The prescribed values at pseudo-time t on every constrained dof (last condition wins).
  void set_targets(double t);
  // Some constrained dof of u is not yet at its prescribed value: the next system lifts
  // (each process tests the dofs it owns; the answer is the same on every process).
  bool pending(const fem::DofLayout& layout, fem::StateView u) const;
  // The constrained dofs of u that its storage holds set to their prescribed values exactly
  // (free of round-off).
  void impose(fem::ResidualView u) const;
  // Constrained rows and columns of A become identity; with lift, the prescribed increment
  // (targets - u) goes into rhs on them and, through the removed columns, into the free rows.
  // A and rhs are in the layout's numbering; each rank zeroes the rows it owns.
  void apply(const fem::DofLayout& layout, Mat A, Vec rhs, fem::StateView u, bool lift) const;

  // 2-norm over the free displacement (and pressure) dofs, from the entries each process
  // owns, the same bits on every process (fem::sum_over_ranks).
  double free_norm(const fem::DofLayout& layout, fem::StateView r) const;
  double free_norm(const fem::DofLayout& layout, Vec v) const;
  // Total force per Dirichlet condition: sum of w_n r_n over its nodes, w the coefficients
  // of the constant 1 in the space's basis (owned entries, summed over processes).
  std::map<std::string, std::array<double, 3>> reactions(const fem::DofLayout& layout, fem::StateView r) const;

private:
  const ElasticityProblem& problem_;
  std::vector<std::vector<int>> bc_nodes_;  // per Dirichlet condition, sorted
  std::vector<PetscInt> constrained_;       // sorted constrained dofs
  std::vector<char> is_constrained_;        // per dof
  std::vector<double> target_;              // prescribed value per constrained dof
};

}  // namespace stiction::nonlinear
