// lu-mumps: global LU by MUMPS (the paper's GlobalLU). Reports MUMPS's own memory figure
// INFOG(22) (MB effectively used), the factorisation flops RINFOG(3) and the ordering that
// actually ran, INFOG(7) (Debian's MUMPS silently falls back to PORD).
//
// Memory guard: when the environment gives the run a memory limit
// (STICTION_MEMORY_LIMIT_MB, set by `stiction bench` for its runs), the first system is
// analysed alone before the first factorisation, and a factorisation whose estimate
// INFOG(17) (MB for all of MUMPS's data, after analysis) exceeds what the process may still
// use is refused: the run ends as a failed set-up whose reason gives the estimate (the
// paper's "—" for GlobalLU at level 2, measured instead of a machine brought down). The
// analysis is repeated by the factorisation itself, once per run.
#include <fmt/format.h>

#include <cstdlib>

#include "common/process_memory.hpp"
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
    if (estimate_mb_ > 0) extra["mumps_estimate_MB"] = estimate_mb_;
  }

  std::string refuse_setup(const nonlinear::NewtonSystem& system) override {
    const char* limit_text = std::getenv("STICTION_MEMORY_LIMIT_MB");
    if (checked_ || !limit_text) return {};
    checked_ = true;
    const double limit_mb = std::strtod(limit_text, nullptr);
    if (!(limit_mb > 0)) return {};
    PetscMat F;
    STICTION_PETSC(MatGetFactor(system.matrix, MATSOLVERMUMPS, MAT_FACTOR_LU, F.out()));
    STICTION_PETSC(MatSetOptionsPrefix(F, options_prefix(name()).c_str()));  // -lu_mumps_mat_mumps_icntl_*
    PetscIS rows, cols;
    STICTION_PETSC(MatGetOrdering(system.matrix, MATORDERINGNATURAL, rows.out(), cols.out()));
    MatFactorInfo info;
    STICTION_PETSC(MatFactorInfoInitialize(&info));
    STICTION_PETSC(MatLUFactorSymbolic(F, system.matrix, rows, cols, &info));
    PetscInt estimate = 0;
    STICTION_PETSC(MatMumpsGetInfog(F, 17, &estimate));
    estimate_mb_ = static_cast<double>(estimate);
    const double in_use = resident_mb(), available = limit_mb - in_use;
    if (estimate_mb_ <= available) return {};
    return fmt::format("MUMPS estimates {:.0f} MB for its factorisation after analysis (INFOG(17)) and the run may "
                       "still use {:.0f} MB (limit {:.0f} MB with {:.0f} MB in use) so it does not factorise",
                       estimate_mb_, available, limit_mb, in_use);
  }

private:
  bool checked_ = false;
  double estimate_mb_ = 0;
};

}  // namespace

std::unique_ptr<nonlinear::LinearSolver> make_lu_mumps(MPI_Comm comm) { return std::make_unique<LuMumps>(comm); }

}  // namespace stiction::solvers
