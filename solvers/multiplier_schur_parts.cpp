#include "multiplier_schur_parts.hpp"

#include "common/error.hpp"

namespace stiction::solvers {

namespace {

// Pi X Pi for a symmetric block-diagonal Pi: Pi^T X Pi.
Mat projected(Mat X, Mat projector) {
  Mat out;
  STICTION_PETSC(MatPtAP(X, projector, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &out));
  return out;
}

}  // namespace

MultiplierSchurParts form_multiplier_schur_parts(const nonlinear::MultiplierSurface& surface) {
  if (!surface.mass || !surface.laplacian || !surface.projector || !surface.constrained || !surface.slip_rows)
    throw Error("contact preconditioner: the system has no multiplier surface", ErrorKind::Internal);
  MultiplierSchurParts parts;
  *parts.mass.out() = projected(surface.mass, surface.projector);
  *parts.laplacian.out() = projected(surface.laplacian, surface.projector);
  // The slip rows' coupling: a slipping node's tangential row depends on u through its slip
  // S_i = B_i u (19), so the Schur complement's row i holds dc_i/dS_i (B A^-1 B^T)_ij, which
  // Pi M Pi (Pi_i = n n^T there) leaves out. In 3D that row's multiplier block loses the
  // direction t2 orthogonal to n and the slip direction a^ when |lambda_t| = mu lambda_n and
  // g_t = 0, as at the start of every increment of a self-contact pair whose nodes slipped
  // in the last one (nothing has moved yet): the approximation's t2 row is then zero and its
  // LU breaks down (block-strips with 0.5 mm grooves, schur-amg, step 8: DIVERGED_NANORINF
  // at the first solve). Approximated like the rest of (32), with B A^-1 B^T ~ s M: rows
  // dc_i/dS_i M_ij over the constrained nodes j (columns unprojected: B^T acts on every
  // component of lambda_j), the same scale s applied by the caller.
  STICTION_PETSC(MatMatMatMult(surface.slip_rows, surface.mass, surface.constrained, MAT_INITIAL_MATRIX,
                               PETSC_DEFAULT, parts.slip_coupling.out()));
  return parts;
}

}  // namespace stiction::solvers
