#pragma once
// Common machinery of the PETSc-based backends: a KSP under the backend's own options
// prefix, defaults from solvers/options/<name>.opts (command-line options win), separately
// timed set-up and solve, the true residual recomputed after every solve, and the KSP view
// as the backend's description. A backend subclasses it only to add its own figures.
//
// Stagnation: a Krylov solve that, at the rate of its last `-<prefix>ksp_stagnation_window`
// iterations (default 500: five GMRES(100) cycles; with one cycle, boomeramg on ironing-2d-
// frictionless was stopped at 175 iterations, 4.4x above its tolerance after a flat cycle,
// where it converges later), would need more than
// `-<prefix>ksp_stagnation_margin` (default 3) times the iterations left before -ksp_max_it
// to reach its tolerance stops as DIVERGED_STAGNATION (0 turns the test off). A solve whose
// recent rate reaches the tolerance within -ksp_max_it is never stopped; a hopeless one
// (boomeramg on an indefinite contact system) ends after a window instead of at -ksp_max_it.
//
// Continuing: a GMRES(m) solve that stagnated can be continued from its iterate as
// GMRES(k m) (continue_longer), k = `-<prefix>ksp_stagnation_restart_factor` (default 3;
// 1 or less turns it off), the longer basis held to `-<prefix>ksp_stagnation_restart_mb`
// (default 1024) MB per process (no continuing when that leaves no longer restart). A
// restarted GMRES that stalls on a few badly placed eigenvalues of the preconditioned
// operator loses what it learnt of them at every restart; a longer cycle keeps it.
// Measured on crossed-tubes-3d level 1 (schur-amg) at t = 75-76: the last system of an
// increment stagnated in GMRES(100) at 0.16-0.24 of its right side after 500 iterations,
// and GMRES(300) solved the same systems to 1e-4 in 561.
//
// Conditioning: a GMRES solve also reports the extreme singular values of the
// preconditioned operator estimated from its own Hessenberg matrix (KSPSetComputeSingularValues:
// no extra operator application, and the iterates are the same), as `sigma_max_estimate`,
// `sigma_min_estimate` and their ratio `condition_estimate`. Restarted GMRES estimates from its
// last cycle only (PETSc's KSPComputeExtremeSingularValues): sigma_max is usually within a
// few percent, sigma_min can be far off when the solve has not converged, so the ratio says
// how hard the preconditioned system is, not its exact condition number.
#include <string>

#include "common/petsc.hpp"
#include "nonlinear/linear_solver.hpp"

namespace stiction::solvers {

// "schur-amg" -> "schur_amg_"
std::string options_prefix(const std::string& backend_name);
// The embedded default options of a backend, shared parts included (empty if it has none).
std::string default_options(const std::string& backend_name);
// The same on one line, without comments ("-ksp_type gmres -pc_type shell ...").
std::string compact_options(const std::string& backend_name);
// Whether the user gave the backend's option -<prefix><key> (on the command line or in
// PETSC_OPTIONS): ask before the backend is created, which inserts its options file's defaults.
bool backend_option_given(const std::string& backend_name, const std::string& key);

class KspSolver : public nonlinear::LinearSolver {
public:
  KspSolver(std::string name, MPI_Comm comm);
  std::string name() const override { return name_; }
  void setup(const nonlinear::NewtonSystem& system) override;
  nonlinear::LinearSolveStats solve(const nonlinear::NewtonSystem& system, Vec x) override;
  std::string describe() const override;
  void apply_preconditioner(Vec in, Vec out) const override;
  void set_relative_tolerance(double rtol) override;
  double relative_tolerance() const override;
  void set_krylov_restart(int restart) override { krylov_restart_ = restart; }
  void release() override;
  bool continue_longer(const nonlinear::NewtonSystem& system, Vec x, nonlinear::LinearSolveStats& s) override;

protected:
  // Backend figures after set-up (factorisation memory, AMG complexity, ...);
  // setup_output is what set-up printed on stdout when capture_setup_output() is true.
  virtual void collect_setup_figures(std::map<std::string, double>& extra) const {}
  virtual bool capture_setup_output() const { return false; }
  const std::string& setup_output() const { return setup_output_; }
  // Hook to configure the KSP/PC from the system (field splits, ...) before KSPSetUp.
  virtual void configure(const nonlinear::NewtonSystem& system) {}
  // Before KSPSetUp: why this system must not be set up (it would not fit in memory, ...),
  // or empty. A reason is reported by solve() as a failed set-up.
  virtual std::string refuse_setup(const nonlinear::NewtonSystem& system) { return {}; }
  // After a successful KSPSetUp: set up what PETSc would leave to the first solve (a field
  // split's inner solvers), so that its time, memory and figures count as the set-up's.
  virtual void set_up_inner_solvers() {}
  KSP ksp() const { return ksp_; }
  // Whether the last setup() built the preconditioner (collect_setup_figures runs either way).
  bool setup_succeeded() const { return setup_failure_.empty(); }

private:
  struct StagnationTest;
  void install_stagnation_test();
  // The restart to continue a stagnated GMRES(m) solve with (continuing above), or m
  // when there is none; n_local is this process's length of a Krylov vector.
  PetscInt continuation_restart(PetscInt m, PetscInt n_local) const;
  bool estimates_singular_values() const;  // GMRES and FGMRES
  void create_ksp();  // a new KSP under the backend's prefix
  std::string name_;
  MPI_Comm comm_;
  PetscKSP ksp_;
  StagnationTest* stagnation_ = nullptr;  // owned by the KSP (its convergence-test context)
  double setup_seconds_ = 0;
  // The options' -ksp_rtol, read at the first set-up: every set-up starts from it, so a
  // tolerance set for one solve does not stay when the options do not name one.
  double options_rtol_ = 0;
  int krylov_restart_ = 0;  // set_krylov_restart's, applied after the options at each set-up (0: the options')
  double krylov_mb_ = 0;  // heap the KSP's work vectors hold: grown over the solves since release()
  std::string setup_output_;
  std::string setup_failure_;  // PETSc's message when the set-up failed (e.g. factorisation)
  std::map<std::string, double> setup_extra_;
};

}  // namespace stiction::solvers
