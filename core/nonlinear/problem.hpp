#pragma once
// A quasi-static hyperelastic problem: the space, a law per cell, and the loads as functions
// of the reference position and the load step (step 0 is the unloaded state).
#include <functional>
#include <string>
#include <vector>

#include "fem/field_space.hpp"
#include "materials/material.hpp"
#include "nonlinear/multiplier_constraint.hpp"

namespace stiction::nonlinear {

// f(X, step, out): a vector (dim entries) at reference point X for load step `step`.
using StepField = std::function<void(const double* X, int step, double* out)>;

struct DirichletCondition {
  std::string name;             // for reports ("block/top")
  int facet_tag = 0;
  std::vector<int> components;  // constrained components (0..dim-1)
  StepField value;              // prescribed displacement
};

struct TractionLoad {  // dead load per reference area
  std::string name;
  int facet_tag = 0;
  StepField value;
};

struct ElasticityProblem {
  const fem::FieldSpace* space = nullptr;
  std::vector<const materials::Material*> cell_material;  // one per cell
  std::vector<DirichletCondition> dirichlet;
  std::vector<TractionLoad> tractions;
  StepField body_force;  // per reference volume; may be empty
  // Contact pairs (owned by the scene); their multipliers follow u (and p) in the system.
  std::vector<MultiplierConstraint*> constraints;
  int n_steps = 1;
};

}  // namespace stiction::nonlinear
