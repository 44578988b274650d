#pragma once
// The runs of a sweep (`stiction bench`) and the estimate of the time its progress line
// gives: what is left, from the wall times of the runs already finished.
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace stiction::harness {

struct BenchRun {
  std::string scene, solver;
  int level = 0;
  int processes = 1;
  std::string key() const;  // scene, level, solver and process count
  std::string id() const;   // the run's directory name: <scene>-L<level>-<solver>[-np<N>]
};

// The run a row of runs.csv records (one process for a sweep older than the column).
BenchRun bench_run_of(const std::map<std::string, std::string>& row);
// That run's directory in the sweep out_dir: <out_dir>/runs/<id>.
std::string run_directory(const std::string& out_dir, const std::map<std::string, std::string>& row);

// Wall time of every finished run, by BenchRun::key().
struct FinishedRuns {
  std::map<std::string, std::pair<BenchRun, double>> by_key;
  void add(const BenchRun& r, double seconds) { by_key[r.key()] = {r, seconds}; }
  bool has(const BenchRun& r) const { return by_key.count(r.key()) > 0; }
};

// Estimated wall time of a run that has not finished, in seconds (0: no basis yet).
double estimate_seconds(const BenchRun& run, const FinishedRuns& finished);

// "about N min left" ("about N s left" under a minute) for runs[current..] (the current one
// `elapsed` seconds in), with the runs that cannot be estimated yet counted apart, and a
// current run past its estimate named.
std::string time_left(const std::vector<BenchRun>& runs, size_t current, double elapsed, const FinishedRuns& finished);

}  // namespace stiction::harness
