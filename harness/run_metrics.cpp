#include "run_metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"
#include "common/process_memory.hpp"

namespace stiction::harness {
namespace {

// One [[step]] row per increment and one [[linear_solve]] row per Newton iteration; `reason`
// replaces the increments' own (IN_PROGRESS for one that has not ended).
void append_rows(const std::vector<nonlinear::StepResult>& steps, toml::array& step_rows, toml::array& solve_rows,
                 const char* reason = nullptr) {
  for (const auto& s : steps) {
    step_rows.push_back(toml::table{{"step", s.step},
                                    {"time", s.time},
                                    {"cut", s.cut},
                                    {"retried", s.retried},
                                    {"completes_step", s.completes_step},
                                    {"converged", s.converged()},
                                    {"reason", reason ? std::string(reason) : nonlinear::to_string(s.reason)},
                                    {"newton_iterations", static_cast<int64_t>(s.iterations.size())},
                                    {"initial_residual", s.initial_residual},
                                    {"reference_residual", s.reference_residual},
                                    {"final_residual", s.final_residual},
                                    {"wall_seconds", s.wall_seconds}});
    int k = 0;
    for (const auto& it : s.iterations) {
      toml::table row{{"step", s.step},
                      {"newton_iteration", ++k},
                      {"converged", it.linear.converged},
                      {"reason", it.linear.reason},
                      {"krylov_iterations", it.linear.iterations},
                      {"initial_residual", it.linear.initial_residual},
                      {"final_residual", it.linear.final_residual},
                      {"setup_seconds", it.linear.setup_seconds},
                      {"solve_seconds", it.linear.solve_seconds},
                      {"assembly_seconds", it.assembly_seconds},
                      {"contact_assembly_seconds", it.contact_assembly_seconds}};
      for (const auto& [name, value] : it.linear.extra) row.insert(name, value);
      solve_rows.push_back(std::move(row));
    }
  }
}

// The rows of `from` whose load step is at most last_step.
void append_rows_up_to(const toml::array* from, int last_step, toml::array& to) {
  if (!from) return;
  for (const auto& node : *from)
    if (const auto* row = node.as_table(); row && (*row)["step"].value<int64_t>().value_or(0) <= last_step)
      to.push_back(*row);
}

}  // namespace

std::optional<EarlierSegments> read_earlier_segments(const std::string& path, const std::string& scene, int level,
                                                     const std::string& solver, int last_step) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  toml::table doc;
  try {
    doc = toml::parse_file(path);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("metrics file '{}' of the run to continue does not read: {}", path, e.description()));
  }
  const auto* run = doc["run"].as_table();
  const std::string its_scene = run ? (*run)["scene"].value<std::string>().value_or("") : "";
  const int its_level = run ? static_cast<int>((*run)["level"].value<int64_t>().value_or(-1)) : -1;
  const std::string its_solver = run ? (*run)["solver"].value<std::string>().value_or("") : "";
  if (its_scene != scene || its_level != level || its_solver != solver)
    throw Error(fmt::format("metrics file '{}' is of scene '{}' level {} solver '{}', not of the run it continues "
                            "('{}' level {} '{}'): give another --metrics path",
                            path, its_scene, its_level, its_solver, scene, level, solver));
  EarlierSegments e;
  append_rows_up_to(doc["step"].as_array(), last_step, e.steps);
  append_rows_up_to(doc["linear_solve"].as_array(), last_step, e.linear_solves);
  e.wall_seconds = (*run)["wall_seconds"].value<double>().value_or(0);
  e.peak_rss_mb = (*run)["peak_rss_mb"].value<double>().value_or(0);
  e.peak_rss_mb_sum = (*run)["peak_rss_mb_sum"].value<double>().value_or(0);
  e.segments = static_cast<int>((*run)["segments"].value<int64_t>().value_or(1));
  return e;
}

void write_metrics(const std::string& path, const scene::SceneView& scene, const RunSummary& summary,
                   const std::vector<nonlinear::StepResult>& steps, const EarlierSegments* earlier,
                   const nonlinear::StepResult* in_progress) {
  toml::array step_rows, solve_rows;
  if (earlier) step_rows = earlier->steps, solve_rows = earlier->linear_solves;
  append_rows(steps, step_rows, solve_rows);
  if (in_progress && !in_progress->iterations.empty()) append_rows({*in_progress}, step_rows, solve_rows, "IN_PROGRESS");
  // The run's totals, summed over the rows of every segment.
  long newton = 0, krylov = 0;
  double assembly = 0, contact_assembly = 0, setup = 0, solve = 0;
  int completed = 0, cuts = 0;
  for (const auto& node : step_rows) {
    const auto& s = *node.as_table();
    completed += s["completes_step"].value<bool>().value_or(false) ? 1 : 0;
    cuts += s["retried"].value<bool>().value_or(false) ? 1 : 0;
    newton += s["newton_iterations"].value<int64_t>().value_or(0);
  }
  for (const auto& node : solve_rows) {
    const auto& s = *node.as_table();
    krylov += s["krylov_iterations"].value<int64_t>().value_or(0);
    assembly += s["assembly_seconds"].value<double>().value_or(0);
    contact_assembly += s["contact_assembly_seconds"].value<double>().value_or(0);
    setup += s["setup_seconds"].value<double>().value_or(0);
    solve += s["solve_seconds"].value<double>().value_or(0);
  }
  const long solves = static_cast<long>(solve_rows.size());
  double peak = summary.processes > 1 ? summary.peak_rss_mb_max : peak_resident_mb();
  double peak_sum = summary.peak_rss_mb_sum;
  if (earlier) peak = std::max(peak, earlier->peak_rss_mb), peak_sum = std::max(peak_sum, earlier->peak_rss_mb_sum);
  int64_t multipliers = 0;
  for (const auto* c : scene.problem->constraints) multipliers += c->n_multipliers();
  toml::table run{{"scene", scene.scene->name},
                  {"level", scene.level},
                  {"solver", summary.solver},
                  {"basis", fem::to_string(scene.space->kind())},
                  {"unknowns", scene.n_dofs()},
                  {"unknowns_u_l", scene.n_linear},
                  {"unknowns_u_q", scene.n_quadratic},
                  {"unknowns_p", scene.n_pressure},
                  {"multipliers", multipliers},
                  {"vertices", scene.n_vertices},
                  {"cells", scene.n_cells},
                  {"converged", summary.converged},
                  {"reason", summary.reason},
                  {"detail", summary.detail},
                  {"load_steps", scene.problem->n_steps()},
                  {"load_steps_completed", completed},
                  {"load_increments_retried", cuts},
                  {"newton_iterations", newton},
                  {"linear_solves", solves},
                  {"krylov_iterations", krylov},
                  {"wall_seconds", summary.wall_seconds + (earlier ? earlier->wall_seconds : 0.0)},
                  {"segments", earlier ? earlier->segments + 1 : 1},
                  {"assembly_seconds", assembly},
                  {"contact_assembly_seconds", contact_assembly},
                  {"setup_seconds", setup},
                  {"solve_seconds", solve},
                  {"newton_rtol", scene.scene->newton.rtol},
                  {"newton_forcing", nonlinear::to_string(scene.scene->newton.forcing)},
                  {"processes", summary.processes},
                  {"peak_rss_mb", peak},
                  {"backend_options", summary.backend_options}};
  if (summary.processes > 1) run.insert("peak_rss_mb_sum", peak_sum);
  toml::table doc{{"run", std::move(run)}, {"step", std::move(step_rows)}, {"linear_solve", std::move(solve_rows)}};
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error(fmt::format("cannot write metrics file '{}'", path));
    out << doc << "\n";
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw Error(fmt::format("cannot write metrics file '{}'", path));
}

RunRecorder::RunRecorder(std::string path, const scene::SceneView& scene, RunSummary base, MPI_Comm comm,
                         std::optional<EarlierSegments> earlier, std::chrono::steady_clock::time_point start,
                         std::chrono::duration<double> in_progress_interval)
    : path_(std::move(path)),
      scene_(scene),
      base_(std::move(base)),
      comm_(comm),
      earlier_(std::move(earlier)),
      start_(start),
      in_progress_interval_(in_progress_interval),
      last_write_(std::chrono::steady_clock::now()) {}

void RunRecorder::add(const nonlinear::StepResult& attempt) {
  attempts_.push_back(attempt);
  in_progress_ = {};  // the attempt carries its iterations
  if (attempt.completes_step)
    write(false, "INCOMPLETE", fmt::format("recorded after load step {}; the run had not ended", attempt.step));
}

void RunRecorder::add_iteration(int step, double t, const nonlinear::NewtonIteration& iteration) {
  if (in_progress_.iterations.empty()) in_progress_.step = step, in_progress_.time = t;
  in_progress_.iterations.push_back(iteration);
  // Rank 0's clock decides for every process: the write is collective.
  int due = std::chrono::steady_clock::now() - last_write_ >= in_progress_interval_ ? 1 : 0;
  MPI_Bcast(&due, 1, MPI_INT, 0, comm_);
  if (due)
    write(false, "INCOMPLETE",
          fmt::format("recorded in load step {} after Newton iteration {}; the run had not ended", step,
                      in_progress_.iterations.size()));
}

void RunRecorder::finish() {
  if (attempts_.empty()) return;  // nothing ran: the earlier record stands
  const auto& last = attempts_.back();
  write(last.converged(), last.converged() ? "CONVERGED" : nonlinear::to_string(last.reason), last.detail);
}

void RunRecorder::write(bool converged, const std::string& reason, const std::string& detail) {
  RunSummary summary = base_;
  summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  summary.converged = converged;
  summary.reason = reason;
  summary.detail = detail;
  const double peak = peak_resident_mb();
  MPI_Reduce(&peak, &summary.peak_rss_mb_max, 1, MPI_DOUBLE, MPI_MAX, 0, comm_);
  MPI_Reduce(&peak, &summary.peak_rss_mb_sum, 1, MPI_DOUBLE, MPI_SUM, 0, comm_);
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  if (rank == 0) write_metrics(path_, scene_, summary, attempts_, earlier_ ? &*earlier_ : nullptr, &in_progress_);
  last_write_ = std::chrono::steady_clock::now();
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
