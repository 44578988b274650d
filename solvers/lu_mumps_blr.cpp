// lu-mumps-blr: MUMPS with block low-rank (BLR) factors (ICNTL(35), compression tolerance
// CNTL(7)) as the preconditioner of GMRES, so that the final residual meets the same
// tolerance as every other Krylov backend (options/lu-mumps-blr.opts). The compression
// tolerance is the backend's cheapening knob: -lu_mumps_blr_mat_mumps_cntl_7 <eps>.
// Run rows carry MUMPS's memory and the factor entries after compression against the
// full-rank estimate of the analysis (solver_figures.hpp: add_mumps_figures); a
// factorisation that would not fit in the run's memory limit, by MUMPS's estimate with
// compressed factors, is refused (mumps_lu_solver.hpp).
#include "mumps_lu_solver.hpp"

namespace stiction::solvers {

std::unique_ptr<nonlinear::LinearSolver> make_lu_mumps_blr(MPI_Comm comm) {
  return std::make_unique<MumpsLuSolver>("lu-mumps-blr", comm);
}

}  // namespace stiction::solvers
