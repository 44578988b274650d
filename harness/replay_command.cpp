#include "replay_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>

#include "common/error.hpp"
#include "registry.hpp"
#include "system_record.hpp"

namespace stiction::harness {

double run_replay(const ReplayOptions& o, const RunInfo& info) {
  const auto dirs = recorded_system_dirs(o.record_dir);
  auto solver = solvers::create_solver(o.solver, PETSC_COMM_WORLD);
  std::ofstream csv;
  if (!o.csv_path.empty()) {
    csv.open(o.csv_path);
    if (!csv) throw Error(fmt::format("cannot write '{}'", o.csv_path));
    csv << format_run_info(info, "# ") << "# solver: " << o.solver << "\n"
        << "system,unknowns,converged,reason,krylov_iterations,initial_residual,final_residual,setup_seconds,"
           "solve_seconds,relative_difference_to_record\n";
  }
  fmt::print("{:<44} {:>9} {:>6} {:>9} {:>9} {:>10} {:>10} {:>9}  {}\n", "system", "unknowns", "its", "setup s",
             "solve s", "residual", "rel.diff", "", "reason");
  double worst = 0;
  for (const auto& dir : dirs) {
    RecordedSystem r = load_system(dir, PETSC_COMM_WORLD);
    PetscVec x, diff;
    STICTION_PETSC(VecDuplicate(r.system.rhs, x.out()));
    STICTION_PETSC(VecZeroEntries(x));
    solver->setup(r.system);
    const auto stats = solver->solve(r.system, x);
    STICTION_PETSC(VecDuplicate(x, diff.out()));
    STICTION_PETSC(VecWAXPY(diff, -1.0, r.solution, x));
    PetscReal dn, rn;
    STICTION_PETSC(VecNorm(diff, NORM_2, &dn));
    STICTION_PETSC(VecNorm(r.solution, NORM_2, &rn));
    const double rel = rn > 0 ? dn / rn : dn;
    worst = std::max(worst, rel);
    PetscInt n;
    STICTION_PETSC(MatGetSize(r.system.matrix, &n, nullptr));
    fmt::print("{:<44} {:>9} {:>6} {:>9.3f} {:>9.3f} {:>10.3e} {:>10.3e} {:>9}  {}\n", r.description, n,
               stats.iterations, stats.setup_seconds, stats.solve_seconds, stats.final_residual, rel, "",
               stats.reason);
    if (csv.is_open()) {
      csv << fmt::format("{},{},{},{},{},{:.6e},{:.6e},{:.4f},{:.4f},{:.6e}\n", r.description, n, stats.converged ? 1 : 0,
                         stats.reason, stats.iterations, stats.initial_residual, stats.final_residual,
                         stats.setup_seconds, stats.solve_seconds, rel);
      csv.flush();
    }
  }
  return worst;
}

}  // namespace stiction::harness
