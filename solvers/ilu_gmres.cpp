// ilu-gmres: GMRES with ILU(k) of the whole system (options/ilu-gmres.opts). The paper
// found ILU "far from sufficient" for these systems; here it is measured.
#include "ksp_solver.hpp"

namespace stiction::solvers {

std::unique_ptr<nonlinear::LinearSolver> make_ilu_gmres(MPI_Comm comm) {
  return std::make_unique<KspSolver>("ilu-gmres", comm);
}

}  // namespace stiction::solvers
