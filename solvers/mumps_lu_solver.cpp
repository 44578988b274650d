#include "mumps_lu_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

#include "common/process_memory.hpp"
#include "solver_figures.hpp"

namespace stiction::solvers {

void MumpsLuSolver::collect_setup_figures(std::map<std::string, double>& extra) const {
  // A refused factorisation never set up the KSP's factor: its figures are the guard's analysis.
  if (setup_succeeded())
    add_mumps_figures(ksp(), "", extra);
  else
    extra.insert(analysis_figures_.begin(), analysis_figures_.end());
  if (estimate_mb_ > 0) extra["mumps_estimate_MB"] = estimate_mb_;
}

std::string MumpsLuSolver::refuse_setup(const nonlinear::NewtonSystem& system) {
  const char* limit_text = std::getenv("STICTION_MEMORY_LIMIT_MB");
  if (memory_checked_ || !limit_text) return {};
  memory_checked_ = true;
  const double limit_mb = std::strtod(limit_text, nullptr);
  if (!(limit_mb > 0)) return {};
  PetscMat F;
  STICTION_PETSC(MatGetFactor(system.matrix, MATSOLVERMUMPS, MAT_FACTOR_LU, F.out()));
  STICTION_PETSC(MatSetOptionsPrefix(F, options_prefix(name()).c_str()));  // -<prefix>mat_mumps_icntl_*
  // No index sets (the "external" ordering PCFactor uses for MUMPS): MUMPS orders with
  // ICNTL(7). Given index sets, PETSc sets ICNTL(7) = 1 and MUMPS analyses the given order
  // (the natural one: 5 811 MB estimated on block-compression level 0, against 540 MB with
  // PORD and 458 MB used).
  MatFactorInfo info;
  STICTION_PETSC(MatFactorInfoInitialize(&info));
  STICTION_PETSC(MatLUFactorSymbolic(F, system.matrix, nullptr, nullptr, &info));
  PetscInt low_rank = 0, estimate = 0;
  STICTION_PETSC(MatMumpsGetIcntl(F, 35, &low_rank));
  const int infog = low_rank > 0 ? 37 : 17;
  STICTION_PETSC(MatMumpsGetInfog(F, infog, &estimate));
  estimate_mb_ = static_cast<double>(estimate);
  analysis_figures_.clear();
  add_mumps_analysis_figures(F, "", analysis_figures_);
  const double in_use = resident_mb(), available = std::max(0.0, limit_mb - in_use);
  if (estimate_mb_ <= available) return {};
  return fmt::format("MUMPS estimates {:.0f} MB for its factorisation after analysis (INFOG({})) and the run may "
                     "still use {:.0f} MB (limit {:.0f} MB with {:.0f} MB in use) so it does not factorise",
                     estimate_mb_, infog, available, limit_mb, in_use);
}

}  // namespace stiction::solvers
