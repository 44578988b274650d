#pragma once
// What one `stiction solve` run measured, written as TOML (--metrics FILE) so the sweep
// harness can run every (scene, solver, level) in a child process and read the results.
//
// [run]            scene, level, solver, basis, unknowns (total: u and p; u_l, u_q, p),
//                  multipliers, vertices, cells, converged,
//                  reason, detail, load_steps, load_steps_completed, newton_iterations,
//                  linear_solves, krylov_iterations, wall_seconds, assembly_seconds,
//                  setup_seconds, solve_seconds, peak_rss_mb, backend_options
// [[step]]         step, converged, reason, newton_iterations, initial_residual,
//                  reference_residual, final_residual, wall_seconds
// [[linear_solve]] step, newton_iteration, converged, reason, krylov_iterations,
//                  initial_residual, final_residual, setup_seconds, solve_seconds,
//                  assembly_seconds, and the backend's extra figures (mumps_memory_MB, ...)
#include <toml++/toml.h>

#include <string>
#include <vector>

#include "nonlinear/newton.hpp"
#include "scene/scene.hpp"

namespace stiction::harness {

struct RunSummary {
  std::string solver;
  std::string backend_options;  // defaults file + command-line PETSc options
  double wall_seconds = 0;
  bool converged = false;
  std::string reason;  // CONVERGED, or the Newton reason of the failed step
  std::string detail;
  // MPI processes of the run and their peak resident memory (the largest and the sum); on
  // one process the peak is this process's own.
  int processes = 1;
  double peak_rss_mb_max = 0, peak_rss_mb_sum = 0;
};

void write_metrics(const std::string& path, const scene::Scene& scene, const RunSummary& summary,
                   const std::vector<nonlinear::StepResult>& steps);

// (set-up + solve) seconds averaged over the [[linear_solve]] records that converged, 0 when
// none did (or there are none): a factorisation that the memory guard refused, or a Krylov
// solve that failed, is no solve of the system and does not count.
double seconds_per_converged_solve(const toml::array* linear_solves);

}  // namespace stiction::harness
