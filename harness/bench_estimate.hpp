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

// Wall time of every finished run, by BenchRun::key(), and, where known, the fraction of it
// spent by the end of each load step (its steps.csv's rows: the shape of the load path).
struct FinishedRuns {
  std::map<std::string, std::pair<BenchRun, double>> by_key;
  std::map<std::string, std::vector<double>> step_fractions;
  void add(const BenchRun& r, double seconds, std::vector<double> fractions = {}) {
    by_key[r.key()] = {r, seconds};
    step_fractions[r.key()] = std::move(fractions);
  }
  bool has(const BenchRun& r) const { return by_key.count(r.key()) > 0; }
};

// The cumulative fraction of a run's wall time at the end of each row of its steps.csv
// (empty when the file is missing or holds no time).
std::vector<double> load_step_fractions(const std::string& steps_csv);

// Estimated wall time of a run that has not finished, in seconds (0: no basis yet).
double estimate_seconds(const BenchRun& run, const FinishedRuns& finished);
// The same for the run under way, `elapsed` seconds in with `steps_done` load steps
// finished: once a step has finished, its elapsed time over the fraction the same backend's
// run one level down had spent by that step; else estimate_seconds.
double estimate_current_seconds(const BenchRun& run, int steps_done, double elapsed, const FinishedRuns& finished);

// "about N min left" ("about N s left" under a minute) for runs[current..] (the current one
// `elapsed` seconds in, `steps_done` load steps finished), with the runs that cannot be
// estimated yet counted apart, and a current run past its estimate named. No run is
// estimated beyond time_limit seconds (the sweep's limit per run; 0: none).
std::string time_left(const std::vector<BenchRun>& runs, size_t current, double elapsed, const FinishedRuns& finished,
                      int steps_done = 0, double time_limit = 0);

}  // namespace stiction::harness
