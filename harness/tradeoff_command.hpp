#pragma once
// `stiction tradeoff`: speed against accuracy on one scene and mesh level. A reference is
// solved first (an exact factorisation, Newton to a tight tolerance); then every backend
// runs at its defaults and at each combination of the knobs (Newton tolerance, Krylov
// tolerance, forcing, a backend's own knob; at its defaults on coarser meshes), each run a child `stiction solve` with a time and memory limit. A
// run's accuracy is its final state against the reference's (solution_accuracy.hpp), its
// cost the run's wall time, linear-solve time, iterations and peak memory; each becomes a
// row of tradeoff.csv, synced as it finishes. report.md (the Pareto front, a plot and the
// recommendations) is rebuilt after every run and by `stiction report DIR`.
#include <string>
#include <vector>

#include "run_info.hpp"

namespace stiction::harness {

struct TradeoffOptions {
  std::string scene;
  int level = 0;
  std::vector<std::string> solvers{"schur-amg"};
  std::vector<double> newton_rtols{1e-4, 1e-6, 1e-8};
  std::vector<double> krylov_rtols{1e-2, 1e-4, 1e-6, 1e-8};  // iterative backends only
  std::vector<std::string> forcings{"fixed"};
  // A backend's own cheapening knob, "option=v1,v2,..." with the PETSc option without its
  // dash (schur_amg_ll_pc_hypre_boomeramg_strong_threshold=0.25,0.5,0.7): each value is a
  // run of the backend whose prefix the option carries, at its default tolerances.
  std::vector<std::string> knobs;
  // Also solve the reference one level finer: how much the mesh changes the answer, beside
  // what the tolerances change (discretisation.csv).
  bool discretisation = false;
  // Mesh levels below `level` at which every backend also runs at its defaults: the mesh as
  // a knob. Their final states are compared with the reference at `level` (compare_levels:
  // contact force and peak pressure, and the norms' differences) and with the analytic
  // solution where the scene models one.
  std::vector<int> coarser_levels;
  std::string reference_solver = "lu-mumps";
  double reference_newton_rtol = 1e-12;
  std::string out_dir = "reports/tradeoff";
  bool resume = false;
  double time_limit_seconds = 3600;
  double memory_limit_mb = 0;  // 0: 90% of the machine's memory
  std::vector<std::string> petsc_options;  // "-prefix_key value" pairs, forwarded by prefix
};

void run_tradeoff(const TradeoffOptions& options, const RunInfo& info);

}  // namespace stiction::harness
