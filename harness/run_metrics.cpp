#include "run_metrics.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <fstream>

#include "common/error.hpp"
#include "common/process_memory.hpp"

namespace stiction::harness {

void write_metrics(const std::string& path, const scene::Scene& scene, const RunSummary& summary,
                   const std::vector<nonlinear::StepResult>& steps) {
  const auto& space = *scene.space;
  toml::array step_rows, solve_rows;
  long newton = 0, solves = 0, krylov = 0;
  double assembly = 0, setup = 0, solve = 0;
  int completed = 0, cuts = 0;
  for (const auto& s : steps) {
    completed += s.completes_step ? 1 : 0;
    cuts += s.retried ? 1 : 0;
    newton += static_cast<long>(s.iterations.size());
    step_rows.push_back(toml::table{{"step", s.step},
                                    {"time", s.time},
                                    {"cut", s.cut},
                                    {"retried", s.retried},
                                    {"converged", s.converged()},
                                    {"reason", nonlinear::to_string(s.reason)},
                                    {"newton_iterations", static_cast<int64_t>(s.iterations.size())},
                                    {"initial_residual", s.initial_residual},
                                    {"reference_residual", s.reference_residual},
                                    {"final_residual", s.final_residual},
                                    {"wall_seconds", s.wall_seconds}});
    int k = 0;
    for (const auto& it : s.iterations) {
      ++solves;
      krylov += it.linear.iterations;
      assembly += it.assembly_seconds;
      setup += it.linear.setup_seconds;
      solve += it.linear.solve_seconds;
      toml::table row{{"step", s.step},
                      {"newton_iteration", ++k},
                      {"converged", it.linear.converged},
                      {"reason", it.linear.reason},
                      {"krylov_iterations", it.linear.iterations},
                      {"initial_residual", it.linear.initial_residual},
                      {"final_residual", it.linear.final_residual},
                      {"setup_seconds", it.linear.setup_seconds},
                      {"solve_seconds", it.linear.solve_seconds},
                      {"assembly_seconds", it.assembly_seconds}};
      for (const auto& [name, value] : it.linear.extra) row.insert(name, value);
      solve_rows.push_back(std::move(row));
    }
  }
  int64_t multipliers = 0;
  for (const auto& c : scene.contacts) multipliers += c->n_multipliers();
  const auto [l0, l1] = space.linear_block();
  const auto [q0, q1] = space.quadratic_block();
  toml::table run{{"scene", scene.name},
                  {"level", scene.level},
                  {"solver", summary.solver},
                  {"basis", fem::to_string(space.kind())},
                  {"unknowns", space.n_dofs()},
                  {"unknowns_u_l", l1 - l0},
                  {"unknowns_u_q", q1 - q0},
                  {"unknowns_p", space.n_pressure_dofs()},
                  {"multipliers", multipliers},
                  {"vertices", scene.mesh.n_vertices()},
                  {"cells", scene.mesh.n_cells()},
                  {"converged", summary.converged},
                  {"reason", summary.reason},
                  {"detail", summary.detail},
                  {"load_steps", scene.problem.n_steps()},
                  {"load_steps_completed", completed},
                  {"load_increments_retried", cuts},
                  {"newton_iterations", newton},
                  {"linear_solves", solves},
                  {"krylov_iterations", krylov},
                  {"wall_seconds", summary.wall_seconds},
                  {"assembly_seconds", assembly},
                  {"setup_seconds", setup},
                  {"solve_seconds", solve},
                  {"newton_rtol", scene.newton.rtol},
                  {"newton_forcing", nonlinear::to_string(scene.newton.forcing)},
                  {"processes", summary.processes},
                  {"peak_rss_mb", summary.processes > 1 ? summary.peak_rss_mb_max : peak_resident_mb()},
                  {"backend_options", summary.backend_options}};
  if (summary.processes > 1) run.insert("peak_rss_mb_sum", summary.peak_rss_mb_sum);
  toml::table doc{{"run", std::move(run)}, {"step", std::move(step_rows)}, {"linear_solve", std::move(solve_rows)}};
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error(fmt::format("cannot write metrics file '{}'", path));
    out << doc << "\n";
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw Error(fmt::format("cannot write metrics file '{}'", path));
}

double seconds_per_converged_solve(const toml::array* linear_solves) {
  double seconds = 0;
  int converged = 0;
  if (linear_solves)
    for (const auto& node : *linear_solves) {
      const auto* s = node.as_table();
      if (!s || !(*s)["converged"].value<bool>().value_or(false)) continue;
      ++converged;
      seconds += (*s)["setup_seconds"].value<double>().value_or(0) + (*s)["solve_seconds"].value<double>().value_or(0);
    }
  return converged ? seconds / converged : 0.0;
}

}  // namespace stiction::harness
