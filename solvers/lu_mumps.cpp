// lu-mumps: global LU by MUMPS (the paper's GlobalLU). Reports MUMPS's own memory figure
// INFOG(22) (MB effectively used), the factorisation flops RINFOG(3) and the ordering that
// actually ran, INFOG(7) (Debian's MUMPS silently falls back to PORD).
#include "ksp_solver.hpp"
#include "solver_figures.hpp"

namespace stiction::solvers {

namespace {

class LuMumps final : public KspSolver {
public:
  explicit LuMumps(MPI_Comm comm) : KspSolver("lu-mumps", comm) {}

protected:
  void collect_setup_figures(std::map<std::string, double>& extra) const override {
    add_mumps_figures(ksp(), "", extra);
  }
};

}  // namespace

std::unique_ptr<nonlinear::LinearSolver> make_lu_mumps(MPI_Comm comm) { return std::make_unique<LuMumps>(comm); }

}  // namespace stiction::solvers
