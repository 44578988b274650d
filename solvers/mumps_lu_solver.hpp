#pragma once
// The MUMPS-based LU backends (lu-mumps, lu-mumps-blr): a KSP whose PC is MUMPS's LU, with
// MUMPS's own figures in the run rows (solver_figures.hpp: add_mumps_figures) and a memory
// guard. When the environment gives the run a memory limit (STICTION_MEMORY_LIMIT_MB, set
// by `stiction bench` for its runs), the first system is analysed alone before the first
// factorisation, with the backend's own MUMPS options, and a factorisation whose estimate
// after analysis exceeds what the process may still use is refused: the run ends as a
// failed set-up whose reason gives the estimate (the paper's "—" for GlobalLU at level 2,
// measured instead of a machine brought down). The estimate is INFOG(17) (MB for all of
// MUMPS's data, full-rank factors) or, when ICNTL(35) asks for block low-rank factors,
// INFOG(37) (the same with the factors compressed at the rate ICNTL(38) assumes; MUMPS 5.5
// users' guide). The analysis is repeated by the factorisation itself, once per run.
#include <map>
#include <string>
#include <utility>

#include "ksp_solver.hpp"

namespace stiction::solvers {

class MumpsLuSolver final : public KspSolver {
public:
  MumpsLuSolver(std::string name, MPI_Comm comm) : KspSolver(std::move(name), comm) {}

protected:
  void collect_setup_figures(std::map<std::string, double>& extra) const override;
  std::string refuse_setup(const nonlinear::NewtonSystem& system) override;

private:
  bool memory_checked_ = false;
  double estimate_mb_ = 0;  // mumps_estimate_MB, once the guard has analysed a system
  std::map<std::string, double> analysis_figures_;  // the guard's analysis: ordering, estimated entries
};

}  // namespace stiction::solvers
