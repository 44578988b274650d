#pragma once
// `stiction solve`: one scene with one backend; VTU/PVD per load step, CSVs of per-step
// quantities (Newton iterations, residuals, linear-solver figures, reactions), of Newton
// iterations and of contact nodes, and a checkpoint after every completed load step.
#include <string>
#include <vector>

#include "run_info.hpp"

namespace stiction::harness {

struct SolveOptions {
  std::string scene;             // path or built-in name
  int level = -1;                // -1: the scene's own
  std::string solver = "lu-mumps";
  std::string out_dir;           // default out/<scene>-L<level>
  std::string metrics_path;      // TOML record of the run for the sweep harness (optional)
  std::string record_dir;        // record every Newton system here (optional)
  std::vector<std::string> record_only;  // with record_dir, only these systems ("STEP:ITERATION"; empty: all)
  bool write_vtu = true;         // --no-vtu turns the scene's VTU output off (sweeps)
  std::string forcing;           // overrides the scene's [newton] forcing when set
  double krylov_rtol = -1;       // overrides the scene's [newton] krylov_rtol when >= 0
  double newton_rtol = -1;       // overrides the scene's [newton] rtol when >= 0
  std::vector<std::string> overrides;  // scene keys set on the command line (--set KEY=VALUE)
  double until = -1;             // stop after the load step that reaches this pseudo-time (< 0: the end)
  bool quick = false;            // stop at the scene's quick_until (the suite's short version)
  std::string restart_dir;       // continue from <dir>/checkpoint.bin (output defaults to <dir>, appended)
  std::string petsc_options;     // the PETSc options given on the command line, for reports
  bool quiet = false;
  bool trace_contact = false;    // print every contact state change per Newton iteration
  bool whole_mesh = false;       // on several processes, every one holds the whole mesh (harness/run_scene.hpp)
};

// Throws stiction::Error (Numerical) when a load step fails, after writing what finished.
void run_solve(const SolveOptions& options, const RunInfo& info);

}  // namespace stiction::harness
