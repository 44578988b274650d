#pragma once
// A direct solve whose factorisation falls back to a pivoting LU.
//
// PETSc's own LU factors in the order its fill-reducing ordering gives, without pivoting: a
// nonsingular matrix with a zero (or vanishing) diagonal entry in that order stops it with a
// zero pivot, and a preonly KSP then returns Inf, which the outer Krylov method reports as
// DIVERGED_NANORINF. The contact level's S~ (contact_pc.hpp) is such a matrix: the normal row
// of a constrained node has no diagonal entry of its own in D, only the scaled mass's, and a
// slipping node's tangential rows are not symmetric.
#include <petscksp.h>

namespace stiction::solvers {

// KSPSetUp(ksp); if its LU or Cholesky factorisation fails, factors again with MUMPS
// (threshold partial pivoting) and keeps MUMPS for the KSP's later set-ups. Returns whether
// it fell back. A failure of MUMPS itself (a singular matrix) is left for the solve to
// report, as PETSc does.
bool set_up_with_pivoting_fallback(KSP ksp);

// Whether the KSP's factorisation is MUMPS's (after a fallback or by choice).
bool factored_by_mumps(KSP ksp);

}  // namespace stiction::solvers
