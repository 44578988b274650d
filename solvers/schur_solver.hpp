#pragma once
// The paper's nested Schur preconditioner in GMRES: HP (10) on [u_l | u_q], wrapped by MHP
// (11) when the system has a pressure block, and by the global contact level (33) when it
// has a multiplier block.
// schur-lu and schur-amg are this class with different option files (A_ll^-1 by MUMPS or
// by one BoomerAMG cycle).
#include <memory>

#include "contact_pc.hpp"
#include "hierarchical_pc.hpp"
#include "ksp_solver.hpp"
#include "mixed_pc.hpp"

namespace stiction::solvers {

class SchurSolver final : public KspSolver {
public:
  SchurSolver(const std::string& name, MPI_Comm comm);
  std::string describe() const override;
  void release() override;
  HierarchicalPreconditioner& hierarchical() { return hp_; }
  MixedPreconditioner* mixed() { return mhp_.get(); }  // null without a pressure block
  ContactPreconditioner* contact() { return contact_.get(); }  // null without contact

protected:
  void configure(const nonlinear::NewtonSystem& system) override;
  bool capture_setup_output() const override { return true; }  // hypre statistics, if any
  void collect_setup_figures(std::map<std::string, double>& extra) const override;

private:
  HierarchicalPreconditioner hp_;
  int processes_ = 1;
  PetscIS displacement_;  // u_l and u_q together, for MHP
  std::unique_ptr<MixedPreconditioner> mhp_;
  std::unique_ptr<ContactPreconditioner> contact_;
};

}  // namespace stiction::solvers
