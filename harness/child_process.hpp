#pragma once
// Runs one command in a child process with a wall-time and a resident-memory limit, so
// each (scene, solver, level) of a sweep has its own peak memory and a run that is killed
// or runs out of memory becomes a row instead of ending the sweep.
#include <functional>
#include <string>
#include <vector>

namespace stiction::harness {

struct ChildLimits {
  double seconds = 3600;
  double memory_mb = 0;  // resident set; 0 = no limit
};

struct ChildResult {
  int exit_code = -1;        // -1 when ended by a signal
  int signal = 0;
  bool hit_time_limit = false;
  bool hit_memory_limit = false;
  double wall_seconds = 0;
  double peak_rss_mb = 0;    // from wait4's rusage: the child's own peak; under a launcher, at
                             // least the polled peak of the launcher and its ranks together
};

// Runs this same executable (/proc/self/exe) with argv; argv[0] is only its display name.
// With a launcher (`mpirun -n 2 ...`), runs launcher + [this executable's path] + argv[1..]
// instead: the memory limit then holds for the launcher and its ranks together, and a run
// over a limit is killed with all of them. stdout/stderr go to the given files.
// on_tick(elapsed) is called about twice a second while the child runs. MPI launcher
// variables are removed from the child's environment so it starts as a singleton (or as
// the new launcher's job).
ChildResult run_child(const std::vector<std::string>& argv, const std::string& stdout_path,
                      const std::string& stderr_path, const ChildLimits& limits,
                      const std::function<void(double)>& on_tick = {}, const std::vector<std::string>& launcher = {});

// The limits of every run of a sweep: memory_mb 0 means 90% of the machine's memory. The
// limit is exported as STICTION_MEMORY_LIMIT_MB, which the runs' MUMPS backends read to
// refuse a factorisation that would not fit (solvers/mumps_lu_solver.hpp).
ChildLimits sweep_limits(double seconds, double memory_mb);

// Status of a finished `stiction solve` child, from how it ended and whether it wrote its
// metrics: ok, newton-failed (exit 3), time-limit, memory-limit, killed (signal N), error.
std::string solve_status(const ChildResult& c, bool have_metrics);

// Path of the running executable (/proc/self/exe).
std::string self_executable();
// Physical memory of the machine in MB.
double physical_memory_mb();

}  // namespace stiction::harness
