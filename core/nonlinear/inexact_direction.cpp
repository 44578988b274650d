#include "nonlinear/inexact_direction.hpp"

#include <algorithm>
#include <cmath>

namespace stiction::nonlinear {

// Measured on ironing-2d-frictionless level 1 (schur-amg), the first clause: the second
// system of a sliding step stagnated at 1.7e-4 against 1e-4 at t = 1.15 (1.735e-4 after
// 1 000 GMRES iterations), at 2.0e-4 and 2.1e-4 at t = 1.26 and 1.2575, and each stopped the
// run. The second: crossed-tubes-3d level 1 (schur-amg) at t = 75.5, the last system of an
// increment (free residual already within its tolerance, the contact residual 4e-7 against
// 1e-7) stagnated at 1.4e-3 of a right side of 1e-5 after 883 GMRES iterations, which the
// first clause refused and the increment was cut.
bool usable_direction(const LinearSolveStats& s, double terminal_residual) {
  const auto rtol = s.extra.find("ksp_rtol");
  if (rtol == s.extra.end() || !(s.initial_residual > 0) || !std::isfinite(s.final_residual)) return false;
  return s.final_residual <= kUsableForcingFactor * rtol->second * s.initial_residual ||
         s.final_residual <= terminal_residual;
}

double terminal_forcing(double rtol, double terminal_residual, double rhs_norm) {
  if (!(rhs_norm > 0) || !(terminal_residual > 0) || !(rtol > 0)) return rtol;
  return std::max(rtol, std::min(kMaxTerminalForcing, terminal_residual / rhs_norm));
}

}  // namespace stiction::nonlinear
