// lu-mumps-blr: MUMPS with block low-rank (BLR) factors (ICNTL(35), compression tolerance
// CNTL(7)) as the preconditioner of GMRES, so that the final residual meets the same
// tolerance as every other Krylov backend (options/lu-mumps-blr.opts). The compression
// tolerance is the backend's cheapening knob: -lu_mumps_blr_mat_mumps_cntl_7 <eps>.
// Run rows carry MUMPS's memory and the factor entries after compression against the
// full-rank estimate of the analysis (solver_figures.hpp: add_mumps_figures).
#include "ksp_solver.hpp"
#include "solver_figures.hpp"

namespace stiction::solvers {

namespace {

class LuMumpsBlr final : public KspSolver {
public:
  explicit LuMumpsBlr(MPI_Comm comm) : KspSolver("lu-mumps-blr", comm) {}

protected:
  void collect_setup_figures(std::map<std::string, double>& extra) const override {
    add_mumps_figures(ksp(), "", extra);
  }
};

}  // namespace

std::unique_ptr<nonlinear::LinearSolver> make_lu_mumps_blr(MPI_Comm comm) {
  return std::make_unique<LuMumpsBlr>(comm);
}

}  // namespace stiction::solvers
