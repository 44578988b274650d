#include "bench_estimate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "csv_table.hpp"

namespace stiction::harness {

std::string BenchRun::key() const { return fmt::format("{}|{}|{}|{}", scene, level, solver, processes); }

std::string BenchRun::id() const {
  return fmt::format("{}-L{}-{}{}", std::filesystem::path(scene).stem().string(), level, solver,
                     processes > 1 ? fmt::format("-np{}", processes) : "");
}

BenchRun bench_run_of(const std::map<std::string, std::string>& row) {
  return {row.at("scene"), row.at("solver"), static_cast<int>(number(row, "level")),
          std::max(1, static_cast<int>(number(row, "processes")))};
}

std::string run_directory(const std::string& out_dir, const std::map<std::string, std::string>& row) {
  return out_dir + "/runs/" + bench_run_of(row).id();
}

// The same scene, backend and process count one level down, times the growth that backend
// showed between those two levels on another scene, or 15 (about n^1.3 for 8x the unknowns)
// when none did; without a run one level down, the mean of the finished runs at this level.
double estimate_seconds(const BenchRun& run, const FinishedRuns& finished) {
  auto seconds = [&](const std::string& scene, const std::string& solver, int level) {
    const auto it = finished.by_key.find(BenchRun{scene, solver, level, run.processes}.key());
    return it == finished.by_key.end() ? 0.0 : it->second.second;
  };
  if (const double below = seconds(run.scene, run.solver, run.level - 1); below > 0) {
    double growth = 15;
    for (const auto& [key, done] : finished.by_key) {
      const auto& [other, t] = done;
      if (other.solver != run.solver || other.scene == run.scene || other.level != run.level ||
          other.processes != run.processes)
        continue;
      if (const double t0 = seconds(other.scene, other.solver, run.level - 1); t0 > 0) growth = t / t0;
    }
    return below * growth;
  }
  double sum = 0;
  int n = 0;
  for (const auto& [key, done] : finished.by_key)
    if (done.first.level == run.level) sum += done.second, ++n;
  return n ? sum / n : 0;
}

std::vector<double> load_step_fractions(const std::string& steps_csv) {
  std::vector<double> cumulative;
  double sum = 0;
  for (const auto& row : read_csv(steps_csv).rows) cumulative.push_back(sum += number(row, "wall_seconds"));
  if (!(sum > 0)) return {};
  for (double& c : cumulative) c /= sum;
  return cumulative;
}

// The load path's shape carries over between levels (the sliding steps take most of a run
// at every level), where a whole-run extrapolation from the steps done would not: the
// pressing steps are the fast ones.
double estimate_current_seconds(const BenchRun& run, int steps_done, double elapsed, const FinishedRuns& finished) {
  if (steps_done > 0) {
    const auto below = finished.step_fractions.find(BenchRun{run.scene, run.solver, run.level - 1, run.processes}.key());
    if (below != finished.step_fractions.end() && static_cast<size_t>(steps_done) <= below->second.size()) {
      const double fraction = below->second[steps_done - 1];
      if (fraction > 0) return elapsed / fraction;
    }
  }
  return estimate_seconds(run, finished);
}

std::string time_left(const std::vector<BenchRun>& runs, size_t current, double elapsed, const FinishedRuns& finished,
                      int steps_done, double time_limit) {
  double left = 0, overrun_estimate = 0;
  int remaining = 0, unknown = 0;
  for (size_t k = current; k < runs.size(); ++k) {
    if (finished.has(runs[k])) continue;
    ++remaining;
    double t =
        k == current ? estimate_current_seconds(runs[k], steps_done, elapsed, finished) : estimate_seconds(runs[k], finished);
    if (time_limit > 0) t = std::min(t, time_limit);  // the sweep stops a run there
    if (t <= 0) ++unknown;
    if (k == current && t > 0 && elapsed > t) overrun_estimate = t;
    left += k == current ? std::max(t - elapsed, 0.0) : t;
  }
  const auto runs_text = [](int n) { return fmt::format("{} run{}", n, n > 1 ? "s" : ""); };
  // Minutes, or seconds under a minute: a 20-second estimate is not "0 min".
  const auto duration = [](double seconds) {
    return seconds < 59.5 ? fmt::format("{:.0f} s", seconds) : fmt::format("{:.0f} min", seconds / 60);
  };
  // Before any run has finished nothing is known, and "0 min left" would mislead.
  if (unknown == remaining) return fmt::format("time left not yet estimable ({} to go)", runs_text(remaining));
  std::string text = fmt::format("about {} left", duration(left));
  if (unknown) text += fmt::format(" + {} not yet estimable", runs_text(unknown));
  // A run past its estimate counts nothing more, which alone would read as a sweep about to end.
  if (overrun_estimate > 0) text += fmt::format(" (this run past its estimate of {})", duration(overrun_estimate));
  return text;
}

}  // namespace stiction::harness
