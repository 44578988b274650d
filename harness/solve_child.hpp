#pragma once
// One `stiction solve` in a child process for the sweeps that compare settings of one scene
// (tradeoff, atlas): the run's directory, its status, and the figures of its metrics.toml.
#include <string>
#include <vector>

#include "child_process.hpp"

namespace stiction::harness {

struct SolveRun {
  std::string status;  // solve_status: ok, newton-failed, time-limit, memory-limit, killed, error
  ChildResult child;
  // From metrics.toml (empty / 0 when the run wrote none); detail is the last line of
  // stderr when the run ended without a Newton verdict.
  std::string reason, detail;
  double newton = 0, solves = 0, krylov = 0, linear_seconds = 0;
  // The run's own wall time, from its start to its last output (the child's is counted by a
  // 200 ms poll and holds the process's start-up); the child's when the run wrote none or was
  // stopped (its record then ends at its last completed load step).
  double wall_seconds = 0;
};

// Runs `stiction solve scene --level level --out run_dir --quiet --no-vtu --metrics ...`
// followed by arguments (which must hold "--solver NAME") and the PETSc options of
// petsc_options whose prefix is that backend's; run_dir is emptied first.
SolveRun run_solve_child(const std::string& scene, int level, const std::vector<std::string>& arguments,
                         const std::vector<std::string>& petsc_options, const std::string& run_dir,
                         const ChildLimits& limits);

// The last non-empty line of a text file ("" when missing).
std::string last_line(const std::string& path);

}  // namespace stiction::harness
