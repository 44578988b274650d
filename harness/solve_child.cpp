#include "solve_child.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "ksp_solver.hpp"

namespace stiction::harness {

namespace fs = std::filesystem;

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

SolveRun run_solve_child(const std::string& scene, int level, const std::vector<std::string>& arguments,
                         const std::vector<std::string>& petsc_options, const std::string& run_dir,
                         const ChildLimits& limits) {
  const auto solver_flag = std::find(arguments.begin(), arguments.end(), "--solver");
  if (solver_flag == arguments.end() || solver_flag + 1 == arguments.end())
    throw Error("run_solve_child: the arguments name no --solver", ErrorKind::Internal);
  const std::string solver = *(solver_flag + 1);
  std::error_code ec;
  fs::remove_all(run_dir, ec);
  fs::create_directories(run_dir, ec);
  std::vector<std::string> argv{"stiction", "solve", scene,     "--level",   std::to_string(level),
                                "--out",           run_dir, "--quiet", "--no-vtu", "--metrics",
                                run_dir + "/metrics.toml"};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  for (const auto& option : petsc_options)
    if (option.rfind("-" + solvers::options_prefix(solver), 0) == 0) {
      std::istringstream words(option);
      for (std::string w; words >> w;) argv.push_back(w);
    }
  SolveRun r;
  r.child = run_child(argv, run_dir + "/stdout.txt", run_dir + "/stderr.txt", limits);
  const std::string metrics_path = run_dir + "/metrics.toml";
  r.status = solve_status(r.child, fs::exists(metrics_path));
  r.wall_seconds = r.child.wall_seconds;
  toml::table metrics;
  bool have_metrics = fs::exists(metrics_path);
  try {
    if (have_metrics) metrics = toml::parse_file(metrics_path);
  } catch (const toml::parse_error&) {
    have_metrics = false;
  }
  if (const toml::table* m = have_metrics ? metrics["run"].as_table() : nullptr) {
    r.reason = (*m)["reason"].value<std::string>().value_or("");
    r.detail = (*m)["detail"].value<std::string>().value_or("");
    r.newton = (*m)["newton_iterations"].value<double>().value_or(0);
    r.solves = (*m)["linear_solves"].value<double>().value_or(0);
    r.krylov = (*m)["krylov_iterations"].value<double>().value_or(0);
    // A run that did not end by itself left the record of its last completed load step: its
    // wall time is the child's, up to the kill.
    if (r.status == "ok" || r.status == "newton-failed")
      r.wall_seconds = (*m)["wall_seconds"].value<double>().value_or(r.wall_seconds);
    r.linear_seconds =
        (*m)["setup_seconds"].value<double>().value_or(0) + (*m)["solve_seconds"].value<double>().value_or(0);
  }
  if (r.status != "ok" && r.status != "newton-failed") r.detail = last_line(run_dir + "/stderr.txt");
  if (r.child.hit_time_limit) r.detail = "stopped after the time limit";
  return r;
}

}  // namespace stiction::harness
