#include "nonlinear/constraint_set.hpp"

#include <algorithm>

namespace stiction::nonlinear {

ConstraintSet::ConstraintSet(const std::vector<MultiplierConstraint*>& constraints) : constraints_(constraints) {
  for (const auto* c : constraints_) {
    offset_.push_back(n_multipliers_);
    n_multipliers_ += c->n_multipliers();
  }
}

std::vector<int> ConstraintSet::multiplier_vertices() const {
  std::vector<int> out;
  for (const auto* c : constraints_) {
    const std::vector<int> v = c->multiplier_vertices();
    out.insert(out.end(), v.begin(), v.end());
  }
  return out;
}

void ConstraintSet::distribute(const fem::DofLayout& layout, PetscInt n_u) {
  for (size_t k = 0; k < constraints_.size(); ++k) {
    std::vector<char> owned(layout.identity() ? 0 : static_cast<size_t>(constraints_[k]->n_multipliers()));
    for (size_t j = 0; j < owned.size(); ++j) owned[j] = layout.owns(n_u + offset_[k] + static_cast<PetscInt>(j));
    constraints_[k]->distribute(layout.comm(), owned);
  }
}

void ConstraintSet::begin_increment(double t_start, fem::StateView u) {
  for (auto* c : constraints_) c->begin_increment(t_start, u);
}

void ConstraintSet::evaluate(double t, fem::StateView u, const std::vector<double>& lambda,
                             fem::ResidualView r_u, std::vector<double>& r_c, SparseEntries* jacobian,
                             PetscInt n_u) const {
  r_c.assign(lambda.size(), 0.0);
  for (size_t k = 0; k < constraints_.size(); ++k)
    constraints_[k]->evaluate(t, u, lambda.data() + offset_[k], r_u, r_c.data() + offset_[k], jacobian,
                              n_u + offset_[k]);
}

void ConstraintSet::evaluate_rows(double t, fem::StateView u, const std::vector<double>& lambda,
                                  std::vector<double>& r_c) const {
  r_c.assign(lambda.size(), 0.0);
  for (size_t k = 0; k < constraints_.size(); ++k)
    constraints_[k]->evaluate_rows(t, u, lambda.data() + offset_[k], r_c.data() + offset_[k]);
}

int ConstraintSet::update_states(double t, fem::StateView u, const std::vector<double>& lambda,
                                 const std::vector<double>& dlambda) {
  int changes = 0;
  for (size_t k = 0; k < constraints_.size(); ++k)
    changes += constraints_[k]->update_states(t, u, lambda.data() + offset_[k], dlambda.data() + offset_[k]);
  return changes;
}

void ConstraintSet::states_held(const std::vector<double>& lambda, const std::vector<double>& dlambda) {
  for (size_t k = 0; k < constraints_.size(); ++k)
    constraints_[k]->states_held(lambda.data() + offset_[k], dlambda.data() + offset_[k]);
}

std::vector<char> ConstraintSet::states() const {
  std::vector<char> all;
  for (const auto* c : constraints_) {
    const auto s = c->states();
    all.insert(all.end(), s.begin(), s.end());
  }
  return all;
}

bool ConstraintSet::all_free() const {
  const std::vector<char> s = states();
  return std::all_of(s.begin(), s.end(), [](char c) { return c == MultiplierConstraint::kFreeState; });
}

MultiplierSurfaceEntries ConstraintSet::describe_surface() const {
  MultiplierSurfaceEntries surface;
  for (size_t k = 0; k < constraints_.size(); ++k) constraints_[k]->describe_surface(surface, offset_[k]);
  return surface;
}

std::vector<ConstraintSummary> ConstraintSet::summaries(const std::vector<double>& lambda) const {
  std::vector<ConstraintSummary> out;
  for (size_t k = 0; k < constraints_.size(); ++k) out.push_back(constraints_[k]->summary(lambda.data() + offset_[k]));
  return out;
}

std::vector<std::vector<double>> ConstraintSet::save_state() const {
  std::vector<std::vector<double>> out;
  for (const auto* c : constraints_) out.push_back(c->save_state());
  return out;
}

void ConstraintSet::restore_state(const std::vector<std::vector<double>>& saved) {
  for (size_t k = 0; k < constraints_.size(); ++k) constraints_[k]->restore_state(saved[k]);
}

void ConstraintSet::visit_changes(const std::vector<char>& before, double t, fem::StateView u,
                                  const std::vector<double>& lambda, const ChangeVisitor& changed) const {
  size_t first = 0;
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const auto* c = constraints_[k];
    const std::vector<char> now = c->states();
    std::vector<MultiplierNode> nodes;
    for (size_t i = 0; i < now.size(); ++i) {
      if (now[i] == before[first + i]) continue;
      if (nodes.empty()) nodes = c->nodes(t, u, lambda.data() + offset_[k]);
      changed(*c, static_cast<int>(i), before[first + i], nodes[i]);
    }
    first += now.size();
  }
}

}  // namespace stiction::nonlinear
