#include "replay_command.hpp"

#include <petsc/private/petscimpl.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>

#include "common/error.hpp"
#include "ksp_solver.hpp"
#include "registry.hpp"
#include "system_record.hpp"

namespace stiction::harness {

ReplayedSolve replay_system(const RecordedSystem& r, nonlinear::LinearSolver& solver, double krylov_rtol,
                            int krylov_restart) {
  ReplayedSolve out;
  out.krylov_rtol = krylov_rtol;
  PetscVec x, diff;
  STICTION_PETSC(VecDuplicate(r.system.rhs, x.out()));
  STICTION_PETSC(VecZeroEntries(x));
  solver.set_krylov_restart(krylov_restart);  // before set-up, as the Newton driver; 0 restores the backend's
  // A whole run analyses its matrix's pattern once and then refactorises the same matrix
  // with new values at each Newton iteration (PETSc's SAME_NONZERO_PATTERN: MUMPS's symbolic
  // analysis, the sub-matrix extraction of the Schur backends are reused). A replayed system
  // is a new matrix: its first set-up pays that analysis, so the set-up timed is a second one
  // of the same matrix with its values marked changed, as at a later Newton iteration.
  const auto t_first = std::chrono::steady_clock::now();
  solver.setup(r.system);
  out.first_setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_first).count();
  // Values unchanged, marked changed (PETSc's documented way, from its implementation header).
  STICTION_PETSC(PetscObjectStateIncrease(reinterpret_cast<PetscObject>(r.system.matrix.get())));
  solver.setup(r.system);
  if (krylov_rtol > 0) solver.set_relative_tolerance(krylov_rtol);  // after set-up, as the Newton driver
  out.stats = solver.solve(r.system, x);
  if (!out.stats.converged) solver.continue_longer(r.system, x, out.stats);  // as the Newton driver does
  if (const auto m = out.stats.extra.find("ksp_gmres_restart"); m != out.stats.extra.end())
    out.krylov_restart = static_cast<int>(m->second);
  STICTION_PETSC(VecDuplicate(x, diff.out()));
  STICTION_PETSC(VecWAXPY(diff, -1.0, r.solution, x));
  PetscReal dn, rn;
  STICTION_PETSC(VecNorm(diff, NORM_2, &dn));
  STICTION_PETSC(VecNorm(r.solution, NORM_2, &rn));
  out.relative_difference = rn > 0 ? dn / rn : dn;
  // The answer checked against the system itself: r = b - A x.
  STICTION_PETSC(MatMult(r.system.matrix, x, diff));
  STICTION_PETSC(VecAYPX(diff, -1.0, r.system.rhs));
  PetscReal residual, bn;
  STICTION_PETSC(VecNorm(diff, NORM_2, &residual));
  STICTION_PETSC(VecNorm(r.system.rhs, NORM_2, &bn));
  out.relative_residual = bn > 0 ? residual / bn : residual;
  if (!std::isfinite(out.relative_residual)) out.stats.converged = false;  // NaN answers are no solve
  out.answer = std::move(x);
  return out;
}

const char* const kReplayColumns =
    "system,unknowns,converged,reason,krylov_iterations,initial_residual,final_residual,setup_seconds,"
    "solve_seconds,relative_difference_to_record,relative_residual,krylov_restart,krylov_rtol,first_setup_seconds";

double replay_krylov_rtol(const std::string& choice, double recorded, bool rtol_given) {
  if (choice == "backend") return 0;
  if (choice == "recorded") return rtol_given ? 0 : recorded;
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(choice, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != choice.size() || !(value > 0 && value < 1))
    throw Error(fmt::format("--krylov-rtol '{}': expected 'recorded', 'backend' or a number in (0, 1)", choice));
  return value;
}

int replay_krylov_restart(const std::string& choice, int recorded, bool restart_given) {
  return choice == "backend" || restart_given ? 0 : recorded;
}

double run_replay(const ReplayOptions& o, const RunInfo& info) {
  const auto dirs = recorded_system_dirs(o.record_dir);
  replay_krylov_rtol(o.krylov_rtol, 0, false);  // a bad choice ends the run before any solve
  const bool rtol_given = solvers::backend_option_given(o.solver, "ksp_rtol");
  const bool restart_given = solvers::backend_option_given(o.solver, "ksp_gmres_restart");
  auto solver = solvers::create_solver(o.solver, PETSC_COMM_WORLD);
  std::ofstream csv;
  if (!o.csv_path.empty()) {
    csv.open(o.csv_path);
    if (!csv) throw Error(fmt::format("cannot write '{}'", o.csv_path));
    csv << format_run_info(info, "# ") << "# solver: " << o.solver << "\n"
        << kReplayColumns << "\n";
  }
  fmt::print("{:<44} {:>9} {:>6} {:>9} {:>9} {:>10} {:>10} {:>10} {:>7} {:>9}  {}\n", "system", "unknowns", "its",
             "setup s", "solve s", "residual", "b-Ax/b", "rel.diff", "restart", "rtol", "reason");
  double worst = 0;
  for (const auto& dir : dirs) {
    RecordedSystem r = load_system(dir, PETSC_COMM_WORLD);
    const ReplayedSolve replayed =
        replay_system(r, *solver, replay_krylov_rtol(o.krylov_rtol, r.krylov_rtol, rtol_given),
                      replay_krylov_restart(o.krylov_rtol, r.krylov_restart, restart_given));
    const auto& stats = replayed.stats;
    const double rel = replayed.relative_difference;
    worst = std::max(worst, rel);
    PetscInt n;
    STICTION_PETSC(MatGetSize(r.system.matrix, &n, nullptr));
    // The tolerance the solve ran to ("backend": the backend's own -ksp_rtol) and its GMRES
    // restart ("-": not a GMRES solve).
    const std::string rtol = replayed.krylov_rtol > 0 ? fmt::format("{:.0e}", replayed.krylov_rtol) : "backend";
    const std::string restart = replayed.krylov_restart > 0 ? std::to_string(replayed.krylov_restart) : "-";
    fmt::print("{:<44} {:>9} {:>6} {:>9.3f} {:>9.3f} {:>10.3e} {:>10.3e} {:>10.3e} {:>7} {:>9}  {}\n", r.description,
               n, stats.iterations, stats.setup_seconds, stats.solve_seconds, stats.final_residual,
               replayed.relative_residual, rel, restart, rtol, stats.reason);
    if (csv.is_open()) {
      csv << fmt::format("{},{},{},{},{},{:.6e},{:.6e},{:.4f},{:.4f},{:.6e},{:.6e},{},{},{:.4f}\n", r.description, n,
                         stats.converged ? 1 : 0, stats.reason, stats.iterations, stats.initial_residual,
                         stats.final_residual, stats.setup_seconds, stats.solve_seconds, rel,
                         replayed.relative_residual,
                         replayed.krylov_restart > 0 ? std::to_string(replayed.krylov_restart) : "",
                         replayed.krylov_rtol > 0 ? fmt::format("{:g}", replayed.krylov_rtol) : "",
                         replayed.first_setup_seconds);
      csv.flush();
    }
    solver->release();  // as the Newton driver before its next system: no set-up held while loading
    if (o.stop_on_failure && !stats.converged) {
      fmt::print("stopped at the first system that did not converge ({} of {})\n", &dir - dirs.data() + 1,
                 dirs.size());
      break;
    }
  }
  return worst;
}

}  // namespace stiction::harness
