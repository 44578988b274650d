#pragma once
// When a Krylov solve that stopped without reaching its tolerance (out of iterations, or
// stagnating) still gives a Newton update. The Newton stopping test does not change, so
// neither does the answer; such a direction only enters one step.
#include "nonlinear/linear_solver.hpp"

namespace stiction::nonlinear {

// A solve within this factor of its relative tolerance is an inexact-Newton direction.
inline constexpr double kUsableForcingFactor = 10;

// True when the solve s, unconverged, is still a usable direction:
//  * its relative residual is within kUsableForcingFactor of its relative tolerance
//    (s.extra["ksp_rtol"]): an inexact Newton iteration's local rate is bounded by its
//    forcing term (Dembo, Eisenstat & Steihaug 1982), so a 1e-3 direction costs at most an
//    iteration more;
//  * or its residual ||b - A x|| is at most terminal_residual, the size below which the
//    linearised model already meets Newton's own stopping test (the caller passes half the
//    smallest of Newton's absolute tolerances on the blocks; Kelley's safeguard on the
//    forcing term, "Iterative Methods for Linear and Nonlinear Equations" (1995), eq. 6.20,
//    applied to a solve that failed). Near convergence the right side is small and a
//    relative 1e-4 asks for digits below the rounding floor of the products.
// Never usable: no tolerance known, a zero right side, a non-finite residual.
bool usable_direction(const LinearSolveStats& s, double terminal_residual);

// The same safeguard on the tolerance a solve is given: rtol, raised so that the solve stops
// once ||b - A x|| is at most terminal_residual (rhs_norm = ||b||), but never above
// kMaxTerminalForcing. A Newton iteration whose right side is already near Newton's
// tolerance needs only that residual: with rtol 1e-4 the last iteration of a load step
// solves 10-100 times tighter than the stopping test reads.
inline constexpr double kMaxTerminalForcing = 0.1;
double terminal_forcing(double rtol, double terminal_residual, double rhs_norm);

}  // namespace stiction::nonlinear
