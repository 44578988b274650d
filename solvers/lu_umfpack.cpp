// lu-umfpack: global LU by SuiteSparse UMFPACK, a second direct solver (sequential only).
#include "ksp_solver.hpp"

namespace stiction::solvers {

std::unique_ptr<nonlinear::LinearSolver> make_lu_umfpack(MPI_Comm comm) {
  return std::make_unique<KspSolver>("lu-umfpack", comm);
}

}  // namespace stiction::solvers
