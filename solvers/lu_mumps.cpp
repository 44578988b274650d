// lu-mumps: global LU by MUMPS (the paper's GlobalLU). Reports MUMPS's own memory figure
// INFOG(22) (MB effectively used), the factorisation flops RINFOG(3) and the ordering that
// actually ran, INFOG(7) (Debian's MUMPS silently falls back to PORD).
#include <petscmat.h>

#include "ksp_solver.hpp"
#include "registry.hpp"

namespace stiction::solvers {

namespace {

class LuMumps final : public KspSolver {
public:
  explicit LuMumps(MPI_Comm comm) : KspSolver("lu-mumps", comm) {}

protected:
  void collect_setup_figures(std::map<std::string, double>& extra) const override {
    PC pc;
    Mat F;
    if (KSPGetPC(ksp(), &pc) || PCFactorGetMatrix(pc, &F)) return;
    MatSolverType type;
    if (MatFactorGetSolverType(F, &type) || std::string(type) != MATSOLVERMUMPS) return;
    PetscInt mem = 0, ordering = 0;
    PetscReal flops = 0;
    if (!MatMumpsGetInfog(F, 22, &mem)) extra["mumps_memory_MB"] = static_cast<double>(mem);
    if (!MatMumpsGetInfog(F, 7, &ordering)) extra["mumps_ordering"] = static_cast<double>(ordering);
    if (!MatMumpsGetRinfog(F, 3, &flops)) extra["mumps_factor_flops"] = flops;
  }
};

}  // namespace

std::unique_ptr<nonlinear::LinearSolver> make_lu_mumps(MPI_Comm comm) { return std::make_unique<LuMumps>(comm); }

}  // namespace stiction::solvers
