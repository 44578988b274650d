// lu-mumps: global LU by MUMPS (the paper's GlobalLU), full-rank factors
// (options/lu-mumps.opts). Reports MUMPS's own memory figure INFOG(22) (MB effectively
// used), the factorisation flops RINFOG(3) and the ordering that actually ran, INFOG(7)
// (Debian's MUMPS silently falls back to PORD); refuses a factorisation that would not fit
// in the run's memory limit (mumps_lu_solver.hpp).
#include "mumps_lu_solver.hpp"

namespace stiction::solvers {

std::unique_ptr<nonlinear::LinearSolver> make_lu_mumps(MPI_Comm comm) {
  return std::make_unique<MumpsLuSolver>("lu-mumps", comm);
}

}  // namespace stiction::solvers
