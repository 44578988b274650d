#pragma once
// Writes each Newton system the backends solve: the tangent of the elastic residual, with
// contact bordered into the augmented matrix (30), the right side -(r_u, r_c), the
// Dirichlet lifting, the field index sets (u_l, u_q, p, lambda), the rigid-body near-null
// space and, for the preconditioners that use them, the pressure mass matrix with the mixed
// law's moduli and the multiplier surface (mass, Laplacian, projectors, slip rows); the
// preconditioners form their Schur approximations from these themselves.
//
// The system lives in the DofLayout's numbering: on one rank that is stiction's own, on
// several the matrix and vectors are distributed, each rank assembles its own cells and
// the rows of the contact blocks it owns. The preconditioner ingredients (pressure mass,
// multiplier surface) are distributed likewise, in their field's block numbering.
//
// Without contact the tangent keeps one matrix over its pattern for the whole run; with
// contact each system is a new matrix (the constraint blocks change pattern with the
// states), so the caller releases the backend's set-up on the old one before assemble().
#include <memory>
#include <vector>

#include "fem/app_view.hpp"
#include "fem/stiffness_matrix.hpp"
#include "nonlinear/constraint_set.hpp"
#include "nonlinear/dirichlet_lifting.hpp"
#include "nonlinear/newton_system.hpp"
#include "nonlinear/problem.hpp"

namespace stiction::nonlinear {

class NewtonSystemBuilder {
public:
  NewtonSystemBuilder(const fem::DofLayout& layout, const ElasticityProblem& problem, PetscInt n_multipliers);

  // The system at (u, lambda) at pseudo-time t for the residual (r_u, r_c) there (each
  // process reads the rows it owns); with lift, the constrained dofs' increment to the
  // lifting's targets enters it. force_scratch (shaped like r_u) takes the constraint forces
  // that the evaluation of their Jacobian writes. Returns the seconds the constraints took:
  // their Jacobian, the bordered matrix and the multiplier surface's blocks.
  double assemble(double t, fem::StateView u, const std::vector<double>& lambda, fem::StateView r_u,
                const std::vector<double>& r_c, const ConstraintSet& constraints, const DirichletLifting& lifting,
                bool lift, fem::ResidualView force_scratch);

  const NewtonSystem& system() const { return system_; }
  // A tangent matrix alive beside the system's (null when the system's matrix is the tangent
  // or, with contact, once the augmented matrix holds its rows): memory the solve cannot use.
  Mat tangent_beside_system() const {
    return stiffness_->mat() == system_.matrix.get() ? nullptr : stiffness_->mat();
  }

private:
  void add_field(const char* name, std::pair<int, int> range, int block_size);
  void border_with_constraints(double t, fem::StateView u, const std::vector<double>& lambda,
                               fem::ResidualView force_scratch,
                               const ConstraintSet& constraints);

  const fem::DofLayout& layout_;
  const ElasticityProblem& problem_;
  std::unique_ptr<fem::StiffnessMatrix> stiffness_;
  NewtonSystem system_;  // its matrix: stiffness_'s, or with contact the augmented matrix built from it
};

// Rigid-body modes of the space (translations, rotations about the centroid) interpolated in
// its basis and orthonormalised: the near-null space handed to AMG.
// The layout's unknowns beyond the space's (the multipliers of a contact system) are zero.
MatNullSpace rigid_body_modes(const fem::DofLayout& layout, const fem::FieldSpace& space);

}  // namespace stiction::nonlinear
