#pragma once
// The problem's multiplier constraints as one block of the Newton system: multiplier k of
// constraint c is unknown n_u + offset(c) + k (the multipliers follow the displacement and
// pressure unknowns, (30)), and every call on the set reaches each constraint with its slice
// of the multipliers. The Newton driver and the system builder see the set, not the
// constraints one by one.
#include <functional>
#include <vector>

#include "fem/app_view.hpp"
#include "fem/dof_layout.hpp"
#include "nonlinear/multiplier_constraint.hpp"

namespace stiction::nonlinear {

class ConstraintSet {
public:
  explicit ConstraintSet(const std::vector<MultiplierConstraint*>& constraints);

  bool empty() const { return n_multipliers_ == 0; }
  PetscInt n_multipliers() const { return n_multipliers_; }
  // The mesh vertex of every multiplier, in the multipliers' order.
  std::vector<int> multiplier_vertices() const;
  size_t size() const { return constraints_.size(); }

  // On several processes: tells each constraint which of its multipliers this process owns
  // (multiplier k of the set is unknown n_u + k of the layout).
  void distribute(const fem::DofLayout& layout, PetscInt n_u);
  void begin_increment(double t_start, fem::StateView u);
  // r_u -= B^T lambda; r_c (resized to n_multipliers) the rows of the current states; with
  // jacobian, the blocks of (30) in the augmented numbering of a system with n_u unknowns
  // before the multipliers.
  void evaluate(double t, fem::StateView u, const std::vector<double>& lambda, fem::ResidualView r_u,
                std::vector<double>& r_c, SparseEntries* jacobian = nullptr, PetscInt n_u = 0) const;
  // r_c alone, for states just updated at an iterate already evaluated.
  void evaluate_rows(double t, fem::StateView u, const std::vector<double>& lambda,
                     std::vector<double>& r_c) const;
  // The state machine (Sec. 4.5) after a Newton update dlambda; returns the changes.
  int update_states(double t, fem::StateView u, const std::vector<double>& lambda,
                    const std::vector<double>& dlambda);
  void states_held(const std::vector<double>& lambda, const std::vector<double>& dlambda);
  // Every constraint's states, concatenated in order.
  std::vector<char> states() const;
  bool all_free() const;
  // Every constraint's multiplier surface, on the multiplier block's numbering [0, m).
  MultiplierSurfaceEntries describe_surface() const;

  std::vector<ConstraintSummary> summaries(const std::vector<double>& lambda) const;
  std::vector<std::vector<double>> save_state() const;
  void restore_state(const std::vector<std::vector<double>>& saved);

  // Calls changed(constraint, node within it, state before, node now) for every node whose
  // state differs from `before` (states() of an earlier moment).
  using ChangeVisitor = std::function<void(const MultiplierConstraint&, int, char, const MultiplierNode&)>;
  void visit_changes(const std::vector<char>& before, double t, fem::StateView u,
                     const std::vector<double>& lambda, const ChangeVisitor& changed) const;

  const std::vector<MultiplierConstraint*>& constraints() const { return constraints_; }

private:
  std::vector<MultiplierConstraint*> constraints_;
  std::vector<PetscInt> offset_;  // first multiplier of each constraint
  PetscInt n_multipliers_ = 0;
};

}  // namespace stiction::nonlinear
