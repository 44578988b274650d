#pragma once
// `stiction replay DIR --solver NAME`: solve recorded Newton systems with any backend and
// report the same statistics as a live run, plus the difference to the recorded solution.
#include <string>

#include "nonlinear/linear_solver.hpp"
#include "run_info.hpp"
#include "system_record.hpp"

namespace stiction::harness {

struct ReplayOptions {
  std::string record_dir;
  std::string solver = "lu-mumps";
  std::string csv_path;  // optional CSV of the table
  // Relative tolerance of each Krylov solve: "recorded" (the recording solve's, so that the
  // counts compare; the backend's own -ksp_rtol for a record of a direct solve, or when the
  // command line gives -<backend>_ksp_rtol), "backend" (the backend's own), or a number.
  // The GMRES restart follows the same choice: the recording solve's (the scene's
  // newton.krylov_restart, else its backend's), except under "backend" or when the command
  // line gives -<backend>_ksp_gmres_restart.
  std::string krylov_rtol = "recorded";
  // Stop at the first system whose solve does not converge (the sweep's sample: a backend
  // that fails one system is not timed on the others).
  bool stop_on_failure = false;
};

// One recorded system solved again: the solve's statistics, the relative tolerance it ran
// to (0: the backend's own), its GMRES restart (0: not a GMRES solve), its relative
// difference to the recorded solution and the relative residual of its own answer,
// ||b - A x|| / ||b||, computed here and not taken from the backend.
struct ReplayedSolve {
  nonlinear::LinearSolveStats stats;
  double krylov_rtol = 0;
  int krylov_restart = 0;
  double relative_difference = 0;
  double relative_residual = 0;
  // The first set-up of the system (the pattern's analysis included); stats.setup_seconds is
  // the second, of the same matrix with new values, which a whole run pays per iteration.
  double first_setup_seconds = 0;
  PetscVec answer;  // the solve's x
};
// krylov_restart 0: the backend's own -ksp_gmres_restart.
ReplayedSolve replay_system(const RecordedSystem& record, nonlinear::LinearSolver& solver, double krylov_rtol,
                            int krylov_restart = 0);
// The tolerance a system recorded at `recorded` (RecordedSystem::krylov_rtol) is replayed to
// under ReplayOptions::krylov_rtol (0: the backend's own); throws on a choice that is
// neither a name nor a number in (0, 1).
double replay_krylov_rtol(const std::string& choice, double recorded, bool rtol_given);
// The GMRES restart a system recorded with `recorded` (RecordedSystem::krylov_restart) is
// replayed with under that choice (0: the backend's own).
int replay_krylov_restart(const std::string& choice, int recorded, bool restart_given);

// The columns of `stiction replay --csv` (the sweep's sample reads them back).
extern const char* const kReplayColumns;

// Returns the largest relative difference to the recorded solutions.
double run_replay(const ReplayOptions& options, const RunInfo& info);

}  // namespace stiction::harness
