#pragma once
// What the Newton driver needs from a linear solver. The backends (solvers/) implement it
// and register by name; the driver sees only this interface.
#include <map>
#include <memory>
#include <string>

#include "nonlinear/newton_system.hpp"

namespace stiction::nonlinear {

struct LinearSolveStats {
  bool converged = false;
  std::string reason;             // PETSc's converged reason, e.g. CONVERGED_RTOL
  int iterations = 0;             // Krylov iterations (0 for a direct solve)
  double initial_residual = 0;    // ||b|| (true residual of the zero guess)
  double final_residual = 0;      // ||b - A x|| recomputed after the solve
  double setup_seconds = 0;       // factorisation / preconditioner set-up for this system
  double solve_seconds = 0;
  std::map<std::string, double> extra;  // backend figures: MUMPS memory, AMG complexity, ...
};

class LinearSolver {
public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  // Factorise / build the preconditioner for this system's matrix.
  virtual void setup(const NewtonSystem& system) = 0;
  // Solve system.matrix x = system.rhs with the last set-up; never throws for a
  // non-converged solve: the reason is in the statistics.
  virtual LinearSolveStats solve(const NewtonSystem& system, Vec x) = 0;
  // The solver's own description (KSPView), for reports.
  virtual std::string describe() const = 0;
  // Drop the last set-up (factors, hierarchies, sub-blocks, Krylov vectors) and every
  // reference to its matrix. The driver calls it before it assembles a system on a new
  // matrix (contact), so the old set-up is not held while the new system is built.
  virtual void release() {}
  // After a solve into x that stopped unconverged: continue it from x with more memory
  // (a longer Krylov basis) and update s to describe the whole solve. False, s and x
  // untouched, when the backend has nothing more to try. The Newton driver calls it only
  // for a solve it could not use as an update.
  virtual bool continue_longer(const NewtonSystem& system, Vec x, LinearSolveStats& s) { return false; }
  // Relative tolerance of the next solve: the inexact-Newton forcing term. Iterative
  // backends apply it after set-up (it overrides their -ksp_rtol); direct ones ignore it.
  virtual void set_relative_tolerance(double rtol) {}
  // The relative tolerance the next solve stops at: after set-up the backend's own
  // (-ksp_rtol), or the last set_relative_tolerance. 0 for a direct backend.
  virtual double relative_tolerance() const { return 0; }
  // Restart of the GMRES solves from the next set-up on, in place of the backend's
  // -ksp_gmres_restart (0: the backend's). Backends without a restarted Krylov method ignore it.
  virtual void set_krylov_restart(int restart) {}
  // One application of the preconditioner of the last set-up (for a direct backend, the
  // triangular solves): out = P^-1 in. For benchmarks and tests.
  virtual void apply_preconditioner(Vec in, Vec out) const = 0;
};

}  // namespace stiction::nonlinear
