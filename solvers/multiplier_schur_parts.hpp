#pragma once
// The constrained parts of the paper's multiplier Schur approximation (32), formed from the
// multiplier surface the constraints describe (nonlinear::MultiplierSurface):
//
//   mass           Pi M_lambda Pi, the paper's (32) before its scale;
//   laplacian      Pi K Pi, which spans the fractional model with Pi M Pi (fractional_schur.hpp);
//   slip_coupling  (dc/dS) M_lambda A, A the identity on the constrained nodes (see the .cpp).
//
// Each is a sparse product over the surface (MatPtAP, MatMatMatMult) in the multiplier
// block's numbering, distributed as the surface matrices are.
#include "common/petsc.hpp"
#include "nonlinear/newton_system.hpp"

namespace stiction::solvers {

struct MultiplierSchurParts {
  PetscMat mass, laplacian, slip_coupling;
};

MultiplierSchurParts form_multiplier_schur_parts(const nonlinear::MultiplierSurface& surface);

}  // namespace stiction::solvers
