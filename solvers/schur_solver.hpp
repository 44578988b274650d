#pragma once
// The paper's nested Schur preconditioner in GMRES. Today: HP (10) on [u_l | u_q]; the
// mixed (MHP, (11)) and contact (global, (33)) levels will wrap it. schur-lu and schur-amg
// are this class with different option files (A_ll^-1 by MUMPS or by one BoomerAMG cycle).
#include "hierarchical_pc.hpp"
#include "ksp_solver.hpp"

namespace stiction::solvers {

class SchurSolver final : public KspSolver {
public:
  SchurSolver(const std::string& name, MPI_Comm comm);
  std::string describe() const override;
  HierarchicalPreconditioner& hierarchical() { return hp_; }

protected:
  void configure(const nonlinear::NewtonSystem& system) override;
  bool capture_setup_output() const override { return true; }  // hypre statistics, if any
  void collect_setup_figures(std::map<std::string, double>& extra) const override;

private:
  HierarchicalPreconditioner hp_;
};

}  // namespace stiction::solvers
