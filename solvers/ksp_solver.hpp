#pragma once
// Common machinery of the PETSc-based backends: a KSP under the backend's own options
// prefix, defaults from solvers/options/<name>.opts (command-line options win), separately
// timed set-up and solve, the true residual recomputed after every solve, and the KSP view
// as the backend's description. A backend subclasses it only to add its own figures.
#include <string>

#include "common/petsc.hpp"
#include "nonlinear/linear_solver.hpp"

namespace stiction::solvers {

// "schur-amg" -> "schur_amg_"
std::string options_prefix(const std::string& backend_name);
// The embedded default options of a backend (empty if it has none).
std::string default_options(const std::string& backend_name);
// The same on one line, without comments ("-ksp_type gmres -pc_type shell ...").
std::string compact_options(const std::string& backend_name);

class KspSolver : public nonlinear::LinearSolver {
public:
  KspSolver(std::string name, MPI_Comm comm);
  std::string name() const override { return name_; }
  void setup(const nonlinear::NewtonSystem& system) override;
  nonlinear::LinearSolveStats solve(const nonlinear::NewtonSystem& system, Vec x) override;
  std::string describe() const override;
  void apply_preconditioner(Vec in, Vec out) const override;
  void set_relative_tolerance(double rtol) override;
  void release() override;

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
  KSP ksp() const { return ksp_; }

private:
  std::string name_;
  PetscKSP ksp_;
  double setup_seconds_ = 0;
  std::string setup_output_;
  std::string setup_failure_;  // PETSc's message when the set-up failed (e.g. factorisation)
  std::map<std::string, double> setup_extra_;
};

}  // namespace stiction::solvers
