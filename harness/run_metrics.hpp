#pragma once
// What one `stiction solve` run measured, written as TOML (--metrics FILE) so the sweep
// harness can run every (scene, solver, level) in a child process and read the results. The
// file is rewritten after every completed load step (reason INCOMPLETE until the run ends),
// and every half minute or so inside a load step, so a killed run leaves the record of the
// linear solves it finished, and a restart from its checkpoint continues that record.
//
// [run]            scene, level, solver, basis, unknowns (total: u and p; u_l, u_q, p),
//                  multipliers, vertices, cells, converged,
//                  reason, detail, load_steps, load_steps_completed, newton_iterations,
//                  linear_solves, krylov_iterations, wall_seconds, segments, assembly_seconds,
//                  setup_seconds, solve_seconds, peak_rss_mb, backend_options
// [[step]]         step, time, cut, retried, completes_step, converged, reason,
//                  newton_iterations, initial_residual, reference_residual, final_residual,
//                  wall_seconds; the last row may be the increment under way when the record
//                  was written (reason IN_PROGRESS: its Newton iterations so far, wall_seconds 0)
// [[linear_solve]] step, newton_iteration, converged, reason, krylov_iterations,
//                  initial_residual, final_residual, setup_seconds, solve_seconds,
//                  assembly_seconds, and the backend's extra figures (mumps_memory_MB, ...)
#include <toml++/toml.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "nonlinear/newton.hpp"
#include "scene/scene.hpp"
#include "scene/scene_view.hpp"

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

// What the earlier segments of a run continued from its checkpoint (`solve --restart`)
// recorded: their rows up to the checkpoint's load step, the wall time and peak memory.
struct EarlierSegments {
  toml::array steps, linear_solves;
  double wall_seconds = 0, peak_rss_mb = 0, peak_rss_mb_sum = 0;
  int segments = 0;
};

// The record at `path` of the run that wrote the checkpoint a restart continues from, its
// rows cut at last_step (the checkpoint's); nullopt when there is no file. A file of another
// scene, level or solver is bad input (exit 2).
std::optional<EarlierSegments> read_earlier_segments(const std::string& path, const std::string& scene, int level,
                                                     const std::string& solver, int last_step);

// Writes the record of `steps` (after the earlier segments' rows, when given): totals summed
// over all rows, wall time summed over the segments, peak memory the largest of them.
// in_progress: the Newton iterations of the increment under way, when there is one (an
// IN_PROGRESS step row; its solves count in the totals, its load step does not).
void write_metrics(const std::string& path, const scene::SceneView& scene, const RunSummary& summary,
                   const std::vector<nonlinear::StepResult>& steps, const EarlierSegments* earlier = nullptr,
                   const nonlinear::StepResult* in_progress = nullptr);

// The --metrics record of a running solve, on every MPI process (the peak memory is reduced
// over them; rank 0 writes). Each attempt of the Newton loop is added; after one that
// completes its load step the record is rewritten with reason INCOMPLETE, before the
// checkpoint, so that a killed run's record holds at least what its checkpoint does.
class RunRecorder {
 public:
  // start: when the process started its work (the wall time counts from there).
  RunRecorder(std::string path, const scene::SceneView& scene, RunSummary base, MPI_Comm comm,
              std::optional<EarlierSegments> earlier, std::chrono::steady_clock::time_point start,
              std::chrono::duration<double> in_progress_interval = std::chrono::seconds(30));
  void add(const nonlinear::StepResult& attempt);
  // One Newton iteration of the increment under way (nonlinear::QuasiStaticSolver's
  // iteration observer): the record is rewritten with it when the last write is at least
  // in_progress_interval old, so that a run stopped inside a long load step (a sweep's time
  // limit) keeps the figures of the solves it finished. Collective.
  void add_iteration(int step, double t, const nonlinear::NewtonIteration& iteration);
  // The final record: CONVERGED, or the reason of the step that failed.
  void finish();

 private:
  void write(bool converged, const std::string& reason, const std::string& detail);
  std::string path_;
  scene::SceneView scene_;
  RunSummary base_;
  MPI_Comm comm_;
  std::optional<EarlierSegments> earlier_;
  std::chrono::steady_clock::time_point start_;
  std::vector<nonlinear::StepResult> attempts_;
  nonlinear::StepResult in_progress_;  // the Newton iterations of the increment under way
  std::chrono::duration<double> in_progress_interval_;
  std::chrono::steady_clock::time_point last_write_;
};

// (set-up + solve) seconds averaged over the [[linear_solve]] records that converged, 0 when
// none did (or there are none): a factorisation that the memory guard refused, or a Krylov
// solve that failed, is no solve of the system and does not count.
double seconds_per_converged_solve(const toml::array* linear_solves);

}  // namespace stiction::harness
