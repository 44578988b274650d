#pragma once
// A quasi-static hyperelastic problem: the space, a law per cell, and the loads as functions
// of the reference position and a pseudo-time t (t = 0 is the unloaded state). Load step k
// ends at step_times[k]; a step that fails may be cut into smaller increments between
// step_times[k-1] and step_times[k], so every load is defined at any t, not only at steps.
#include <functional>
#include <string>
#include <vector>

#include "fem/field_space.hpp"
#include "materials/material.hpp"
#include "nonlinear/multiplier_constraint.hpp"

namespace stiction::nonlinear {

// f(X, t, out): a vector (dim entries) at reference point X at pseudo-time t.
using TimeField = std::function<void(const double* X, double t, double* out)>;

struct DirichletCondition {
  std::string name;             // for reports ("block/top")
  int facet_tag = 0;
  std::vector<int> components;  // constrained components (0..dim-1)
  TimeField value;              // prescribed displacement
};

struct TractionLoad {  // dead load per reference area
  std::string name;
  int facet_tag = 0;
  TimeField value;
};

struct ElasticityProblem {
  const fem::FieldSpace* space = nullptr;
  std::vector<const materials::Material*> cell_material;  // one per cell
  std::vector<DirichletCondition> dirichlet;
  std::vector<TractionLoad> tractions;
  TimeField body_force;  // per reference volume; may be empty
  // Contact pairs (owned by the scene); their multipliers follow u (and p) in the system.
  std::vector<MultiplierConstraint*> constraints;
  std::vector<double> step_times{0.0, 1.0};  // t_0 = 0 < t_1 < ... < t_n: the load steps
  int n_steps() const { return static_cast<int>(step_times.size()) - 1; }
  // The first load step that reaches pseudo-time t (n_steps when none does).
  int step_reaching(double t) const;
};

// t_k = k / n for k = 0..n: n equal load steps over the unit pseudo-time.
std::vector<double> uniform_step_times(int n_steps);

}  // namespace stiction::nonlinear
