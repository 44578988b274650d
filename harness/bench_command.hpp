#pragma once
// `stiction bench`: the sweep scene x solver x mesh level. Each run is a child
// `stiction solve ... --metrics` with a time and memory limit; its figures become a row of
// runs.csv (one per run) and rows of steps.csv (one per linear solve), each written and
// synced at once; report.md is rebuilt from the CSVs after every run (`stiction report`
// rebuilds it alone). With --sample, one whole run per scene and level (the path backend's)
// records a sample of its Newton systems and every backend replays them in a process of its
// own (samples.csv; bench_sample.hpp). A sweep refuses an existing runs.csv without
// --resume, and a resumed one refuses a binary of another revision unless told otherwise;
// every row names the revision that made it.
#include <string>
#include <vector>

#include "run_info.hpp"

namespace stiction::harness {

struct BenchOptions {
  std::vector<std::string> scenes;   // empty: every built-in scene
  std::vector<std::string> solvers;  // empty: every registered backend
  std::vector<int> levels{0};
  std::vector<int> ranks{1};         // MPI processes per run (above 1: under mpirun)
  std::string out_dir = "reports/bench";
  bool resume = false;
  bool quick = false;                // each scene's short version (its load.quick_until)
  double time_limit_seconds = 3600;
  double memory_limit_mb = 0;        // 0: 90% of the machine's memory
  std::vector<std::string> petsc_options;  // "-prefix_key value" pairs, forwarded by prefix
  std::string forcing;                     // Newton forcing for every run (empty: the scene's)
  double krylov_rtol = -1;                 // Krylov tolerance for every run (< 0: the scene's)
  // The recorded sample (bench_sample.hpp): "STEP:ITERATION" systems that the path
  // backend's whole run of each scene and level records and every backend then replays.
  // Empty: every backend runs whole (scene x solver x level).
  std::vector<std::string> sample;
  std::string path_solver = "schur-amg";
  std::vector<std::string> whole;          // with a sample, more whole runs: "SOLVER:LEVEL"
  bool allow_other_revision = false;       // --resume with a binary of another revision
};

void run_bench(const BenchOptions& options, const RunInfo& info);

}  // namespace stiction::harness
