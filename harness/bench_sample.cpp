#include "bench_sample.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "csv_table.hpp"
#include "solve_child.hpp"

namespace stiction::harness {

const char* const kSampleColumns =
    "scene,level,solver,status,systems,systems_converged,unknowns,krylov_per_solve,setup_seconds_per_solve,"
    "solve_seconds_per_solve,seconds_per_linear_solve,peak_rss_mb,max_relative_residual,max_relative_difference,"
    "path_linear_solves,projected_total_seconds,first_setup_seconds_per_solve,revision,detail";

namespace {

using Row = std::map<std::string, std::string>;

std::string scene_stem(const std::string& scene) { return std::filesystem::path(scene).stem().string(); }

// An answer passes when ||b - A x|| / ||b|| is within 10x the tolerance the recording solve
// was asked for (a preconditioned Krylov method stops on its own norm, not this one), and
// within 1e-8 when the system was recorded from a direct solve.
bool accurate(const Row& r) {
  const double residual = number(r, "relative_residual"), rtol = number(r, "krylov_rtol");
  return std::isfinite(residual) && residual <= (rtol > 0 ? 10 * rtol : 1e-8);
}

// How a replay child ended, when it did not end by itself with exit 0.
std::string abnormal_end(const ChildResult& c, const std::string& run_dir) {
  if (c.hit_memory_limit) return "memory-limit";
  if (c.hit_time_limit) return "time-limit";
  if (c.signal) return fmt::format("killed (signal {})", c.signal);
  if (c.exit_code != 0) return "error: " + last_line(run_dir + "/stderr.txt");
  return "";
}

}  // namespace

std::string sample_record_dir(const std::string& out_dir, const std::string& scene, int level) {
  return fmt::format("{}/records/{}-L{}", out_dir, scene_stem(scene), level);
}

std::string sample_run_dir(const std::string& out_dir, const std::string& scene, int level, const std::string& solver) {
  return fmt::format("{}/samples/{}-L{}-{}", out_dir, scene_stem(scene), level, solver);
}

std::vector<std::string> record_arguments(const std::string& record_dir, const std::vector<std::string>& systems) {
  return {"--record", record_dir, "--record-only", fmt::format("{}", fmt::join(systems, ","))};
}

std::vector<std::string> replay_arguments(const std::string& exe, const std::string& record_dir,
                                          const std::string& solver, const std::string& run_dir) {
  return {exe, "replay", record_dir, "--solver", solver, "--csv", run_dir + "/replay.csv", "--stop-on-failure"};
}

double projected_total_seconds(const Row& path_row, double seconds_per_solve) {
  if (path_row.empty() || path_row.at("status") != "ok" || seconds_per_solve <= 0) return 0;
  const double solves = number(path_row, "linear_solves");
  const double path_solving = number(path_row, "setup_seconds") + number(path_row, "solve_seconds");
  return number(path_row, "wall_seconds") - path_solving + solves * seconds_per_solve;
}

std::string sample_row(const std::string& scene, int level, const std::string& solver, const std::string& run_dir,
                       const ChildResult& child, const Row& path_row, int systems_requested,
                       const std::string& revision) {
  const CsvTable replay = read_csv(run_dir + "/replay.csv");
  int converged = 0;
  double krylov = 0, setup = 0, solve = 0, first_setup = 0, worst_residual = 0, worst_difference = 0, unknowns = 0;
  std::string failure, inaccurate;
  for (const auto& r : replay.rows) {
    unknowns = number(r, "unknowns");
    worst_residual = std::max(worst_residual, number(r, "relative_residual"));
    worst_difference = std::max(worst_difference, number(r, "relative_difference_to_record"));
    if (number(r, "converged") != 1) {
      failure = fmt::format("{}: {}", r.at("system"), r.at("reason"));
      continue;
    }
    if (!accurate(r) && inaccurate.empty())
      inaccurate = fmt::format("{}: ||b - Ax|| / ||b|| = {} above 10x its tolerance {}", r.at("system"),
                               r.at("relative_residual"), r.at("krylov_rtol"));
    ++converged;
    krylov += number(r, "krylov_iterations");
    setup += number(r, "setup_seconds");
    first_setup += number(r, "first_setup_seconds");
    solve += number(r, "solve_seconds");
  }
  const int systems = static_cast<int>(replay.rows.size());
  std::string status = abnormal_end(child, run_dir), detail;
  if (!status.empty()) {
    detail = status.rfind("error: ", 0) == 0 ? status.substr(7) : fmt::format("after {:.0f} s", child.wall_seconds);
    status = status.substr(0, status.find(':'));
    if (systems > 0) detail += fmt::format("; {} of {} systems solved before", systems, systems_requested);
  } else if (systems == 0) {
    status = "error", detail = "replay wrote no system";
  } else if (!failure.empty()) {
    status = "failed", detail = "did not converge on " + failure + " (the systems after it were not solved)";
  } else if (!inaccurate.empty()) {
    status = "inaccurate", detail = inaccurate;
  } else {
    status = "ok";
  }
  if (systems_requested > 0 && systems < systems_requested && status == "ok")
    detail = fmt::format("{} of the {} requested systems exist on this path", systems, systems_requested);
  const double per = converged > 0 ? 1.0 / converged : 0.0;
  const double seconds_per_solve = (setup + solve) * per;
  const double projected = status == "ok" ? projected_total_seconds(path_row, seconds_per_solve) : 0.0;
  return fmt::format("{},{},{},{},{},{},{:.0f},{:.1f},{:.4f},{:.4f},{:.4f},{:.1f},{:.3e},{:.3e},{},{},{:.4f},{},{}", scene,
                     level, solver, status, systems, converged, unknowns, krylov * per, setup * per, solve * per,
                     seconds_per_solve, child.peak_rss_mb, worst_residual, worst_difference,
                     path_row.empty() ? std::string() : fmt::format("{:.0f}", number(path_row, "linear_solves")),
                     projected > 0 ? fmt::format("{:.1f}", projected) : std::string(), first_setup * per, revision,
                     csv_field(detail));
}

std::string unrecorded_sample_row(const std::string& scene, int level, const std::string& solver,
                                  const std::string& why, const std::string& revision) {
  return fmt::format("{},{},{},no-record,0,0,0,0,0,0,0,0,0,0,,,0,{},{}", scene, level, solver, revision, csv_field(why));
}

}  // namespace stiction::harness
