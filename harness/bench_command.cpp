#include "bench_command.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include <fmt/ranges.h>
#include <unistd.h>

#include "bench_estimate.hpp"
#include "bench_report.hpp"
#include "bench_sample.hpp"
#include "builtin_scenes.hpp"
#include "checkpoint.hpp"
#include "child_process.hpp"
#include "common/error.hpp"
#include "csv_table.hpp"
#include "ksp_solver.hpp"
#include "registry.hpp"
#include "run_metrics.hpp"
#include "solve_child.hpp"
#include "sweep_table.hpp"
#include "system_record.hpp"

namespace stiction::harness {

namespace fs = std::filesystem;

namespace {

const char* kRunColumns =
    "scene,level,solver,processes,status,converged,reason,unknowns,unknowns_u_l,unknowns_u_q,unknowns_p,multipliers,vertices,"
    "cells,load_steps,"
    "load_steps_completed,newton_iterations,linear_solves,krylov_iterations,krylov_per_linear_solve,wall_seconds,"
    "assembly_seconds,contact_assembly_seconds,setup_seconds,solve_seconds,seconds_per_linear_solve,peak_rss_mb,peak_rss_mb_per_process,mumps_memory_mb,"
    "mumps_factor_fraction,amg_operator_complexity,krylov_rtol,mumps_ordering,newton_rtol,newton_forcing,petsc_options,"
    "revision,detail";
const char* kStepColumns =
    "scene,level,solver,processes,step,newton_iteration,converged,reason,krylov_iterations,initial_residual,final_residual,"
    "assembly_seconds,setup_seconds,solve_seconds";

// `mpirun -n N` for a run on N > 1 processes (as root Open MPI needs --allow-run-as-root;
// more processes than cores need --oversubscribe, and their times are not a measurement).
std::vector<std::string> launcher_for(int processes) {
  if (processes <= 1) return {};
  std::vector<std::string> l{"mpirun", "-n", std::to_string(processes)};
  if (geteuid() == 0) l.push_back("--allow-run-as-root");
  if (processes > static_cast<int>(std::thread::hardware_concurrency())) l.push_back("--oversubscribe");
  return l;
}

int count_data_lines(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  int n = -1;  // the header
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') ++n;
  return std::max(n, 0);
}

// MUMPS's ordering codes (ICNTL(7) / INFOG(7), MUMPS 5.5 users' guide).
std::string mumps_ordering_name(int code) {
  switch (code) {
    case 0: return "AMD";
    case 1: return "given";
    case 2: return "AMF";
    case 3: return "SCOTCH";
    case 4: return "PORD";
    case 5: return "METIS";
    case 6: return "QAMD";
  }
  return fmt::format("code {}", code);
}

// A run that an earlier sweep started and did not finish (killed with the sweep, or the
// machine went down): its directory holds a checkpoint and the record of its finished load
// steps, and `--resume` continues it from there instead of starting it again.
struct Interrupted {
  int last_step = 0;           // the checkpoint's load step
  // The run had ended (its record has a verdict; the sweep stopped before writing its row):
  // the row comes from the record, and nothing runs again.
  bool ended = false, converged = false;
  double wall_seconds = 0;     // of the earlier segments, up to their last completed load step
  double peak_rss_mb = 0;      // the largest of the earlier segments'
  int segments = 0;
};

std::optional<Interrupted> interrupted_run(const BenchRun& run, const std::string& run_dir) {
  const std::string checkpoint = run_dir + "/checkpoint.bin", metrics_path = run_dir + "/metrics.toml";
  if (!fs::exists(checkpoint) || !fs::exists(metrics_path)) return std::nullopt;
  try {
    const toml::table metrics = toml::parse_file(metrics_path);
    const auto* m = metrics["run"].as_table();
    if (!m || (*m)["solver"].value<std::string>() != run.solver || (*m)["level"].value<int64_t>() != run.level ||
        (*m)["processes"].value<int64_t>().value_or(1) != run.processes)
      return std::nullopt;
    Interrupted i;
    i.last_step = read_checkpoint(checkpoint).state.step;
    i.wall_seconds = (*m)["wall_seconds"].value<double>().value_or(0);
    i.peak_rss_mb = (*m)[run.processes > 1 ? "peak_rss_mb_sum" : "peak_rss_mb"].value<double>().value_or(0);
    i.segments = static_cast<int>((*m)["segments"].value<int64_t>().value_or(1));
    const std::string reason = (*m)["reason"].value<std::string>().value_or("INCOMPLETE");
    i.ended = reason != "INCOMPLETE";
    i.converged = (*m)["converged"].value<bool>().value_or(false);
    return i;
  } catch (const toml::parse_error&) {
    return std::nullopt;
  } catch (const Error&) {  // a checkpoint that does not read: the run starts again
    return std::nullopt;
  }
}

// What a run's [[linear_solve]] records say beyond its totals: the backends' own figures
// for its row, and its steps.csv lines.
struct SolveFigures {
  double mumps_memory_mb = 0;  // the largest, of the whole system's or the P1 block's factorisation
  // Factor entries as stored (after block low-rank compression) and as the analysis
  // estimated them at full rank, summed over the factorisations: their ratio is the BLR
  // compression (1 without it, up to the pivoting's delays).
  double factor_entries = 0, full_rank_entries = 0;
  double amg_complexity_sum = 0;
  int amg_solves = 0;
  double krylov_rtol = 0;
  std::string ordering;  // the fill-reducing ordering MUMPS ran (INFOG(7)), of the whole system or the P1 block
  std::string steps_csv;
};

SolveFigures solve_figures(const BenchRun& run, const toml::array* solves) {
  SolveFigures f;
  if (!solves) return f;
  for (const auto& node : *solves) {
    const auto& s = *node.as_table();
    for (const std::string prefix : {"", "ll_"}) {
      f.mumps_memory_mb = std::max(f.mumps_memory_mb, s[prefix + "mumps_memory_MB"].value<double>().value_or(0.0));
      if (const auto code = s[prefix + "mumps_ordering"].value<double>())
        f.ordering = mumps_ordering_name(static_cast<int>(*code));
      const auto stored = s[prefix + "mumps_factor_entries"].value<double>();
      const auto full_rank = s[prefix + "mumps_factor_entries_full_rank"].value<double>();
      if (stored && full_rank && *full_rank > 0) f.factor_entries += *stored, f.full_rank_entries += *full_rank;
    }
    if (auto c = s["amg_operator_complexity"].value<double>()) f.amg_complexity_sum += *c, ++f.amg_solves;
    f.krylov_rtol = s["ksp_rtol"].value<double>().value_or(f.krylov_rtol);
    f.steps_csv += fmt::format("{},{},{},{},{},{},{},{},{},{:.6e},{:.6e},{:.4f},{:.4f},{:.4f}\n", run.scene, run.level,
                               run.solver, run.processes, s["step"].value<int64_t>().value_or(0),
                               s["newton_iteration"].value<int64_t>().value_or(0),
                               s["converged"].value<bool>().value_or(false) ? 1 : 0,
                               s["reason"].value<std::string>().value_or(""),
                               s["krylov_iterations"].value<int64_t>().value_or(0),
                               s["initial_residual"].value<double>().value_or(0),
                               s["final_residual"].value<double>().value_or(0),
                               s["assembly_seconds"].value<double>().value_or(0),
                               s["setup_seconds"].value<double>().value_or(0), s["solve_seconds"].value<double>().value_or(0));
  }
  return f;
}

// Appends the run's row to runs.csv and its linear solves to steps.csv; returns its wall time.
double write_rows(const std::string& out, const BenchRun& run, const ChildResult& child, const std::string& run_dir,
                  const std::string& petsc_options, const std::optional<Interrupted>& continued,
                  const std::string& revision) {
  const std::string metrics_path = run_dir + "/metrics.toml";
  toml::table metrics;
  bool have_metrics = fs::exists(metrics_path);
  if (have_metrics) {
    try {
      metrics = toml::parse_file(metrics_path);
    } catch (const toml::parse_error&) {
      have_metrics = false;
    }
  }
  const std::string status = solve_status(child, have_metrics);
  const toml::table empty;
  const toml::table& m = have_metrics && metrics["run"].as_table() ? *metrics["run"].as_table() : empty;
  auto num = [&](const char* k) { return m[k].value<double>().value_or(0.0); };
  const SolveFigures figures = solve_figures(run, metrics["linear_solve"].as_array());
  const double solves = num("linear_solves");
  // On several processes the job's peak is the sum over its processes (metrics.toml, each
  // process's own VmHWM); on one, the child's.
  const bool several = run.processes > 1;
  double peak_total = several && have_metrics ? num("peak_rss_mb_sum") : child.peak_rss_mb;
  double peak_per_process = several && have_metrics ? num("peak_rss_mb") : child.peak_rss_mb;
  double wall = child.wall_seconds;
  std::string detail = m["detail"].value<std::string>().value_or("");
  if (status != "ok" && status != "newton-failed") detail = last_line(run_dir + "/stderr.txt");
  if (continued) {
    wall += continued->wall_seconds;
    peak_total = std::max(peak_total, continued->peak_rss_mb);
    if (!several) peak_per_process = peak_total;
  }
  if (child.hit_time_limit)
    detail = solves > 0 ? fmt::format("stopped after {:.0f} s; figures per solve over the {:.0f} linear solves it "
                                      "finished ({:.0f} of {:.0f} load steps completed)",
                                      wall, solves, num("load_steps_completed"), num("load_steps"))
                        : fmt::format("stopped after {:.0f} s", wall);
  if (continued && continued->ended)
    detail += fmt::format("{}row from the run's record: the run had ended, the sweep had not written its row",
                          detail.empty() ? "" : "; ");
  else if (continued)
    detail += fmt::format("{}continued from its checkpoint after load step {} ({} segments; wall time and peak over all)",
                          detail.empty() ? "" : "; ", continued->last_step, continued->segments + 1);
  const std::string row = fmt::format(
      "{},{},{},{},{},{},{},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.0f},{:.2f},{:.3f},"
      "{:.3f},{:.3f},{:.3f},{:.3f},{:.4f},"
      "{:.1f},{:.1f},{:.0f},{},{:.3f},{},{},{},{},{},{},{}",
      run.scene, run.level, run.solver, run.processes, status, m["converged"].value<bool>().value_or(false) ? 1 : 0,
      csv_field(m["reason"].value<std::string>().value_or(status)), num("unknowns"), num("unknowns_u_l"),
      num("unknowns_u_q"), num("unknowns_p"), num("multipliers"), num("vertices"), num("cells"), num("load_steps"), num("load_steps_completed"), num("newton_iterations"), solves,
      num("krylov_iterations"), solves > 0 ? num("krylov_iterations") / solves : 0.0, wall,
      num("assembly_seconds"), num("contact_assembly_seconds"), num("setup_seconds"), num("solve_seconds"),
      seconds_per_converged_solve(metrics["linear_solve"].as_array()), peak_total, peak_per_process,
      figures.mumps_memory_mb,
      figures.full_rank_entries > 0 ? fmt::format("{:.3f}", figures.factor_entries / figures.full_rank_entries) : "",
      figures.amg_solves ? figures.amg_complexity_sum / figures.amg_solves : 0.0,
      figures.krylov_rtol > 0 ? fmt::format("{:g}", figures.krylov_rtol) : "", figures.ordering,
      m["newton_rtol"] ? fmt::format("{:g}", num("newton_rtol")) : std::string(),
      m["newton_forcing"].value<std::string>().value_or(""), csv_field(petsc_options), csv_field(revision),
      csv_field(detail));
  if (!figures.steps_csv.empty()) append_durably(out + "/steps.csv", figures.steps_csv);
  append_durably(out + "/runs.csv", row);
  return wall;
}

// The --whole items "SOLVER:LEVEL" as (solver, level) pairs; throws on any other form.
std::vector<std::pair<std::string, int>> whole_runs(const BenchOptions& o) {
  std::vector<std::pair<std::string, int>> runs;
  for (const auto& item : o.whole) {
    const size_t colon = item.rfind(':');
    size_t used = 0;
    int level = -1;
    try {
      if (colon != std::string::npos) level = std::stoi(item.substr(colon + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (colon == std::string::npos || colon == 0 || used == 0 || colon + 1 + used != item.size())
      throw Error(fmt::format("--whole '{}': expected SOLVER:LEVEL (e.g. lu-mumps:0)", item));
    runs.emplace_back(item.substr(0, colon), level);
  }
  return runs;
}

// Refuses, before any run, a sweep that would fail or silently ignore part of itself.
void check_sweep(const BenchOptions& o, const std::vector<std::string>& scenes,
                 const std::vector<std::string>& solvers_list) {
  for (const auto& s : scenes)
    if (!builtin_scenes().count(s) && !fs::is_regular_file(s))
      throw Error(fmt::format("scene '{}' is neither a file nor a built-in scene", s));
  std::set<std::string> known;
  for (const auto& b : solvers::backends()) known.insert(b.name);
  for (const auto& s : solvers_list)
    if (!known.count(s)) throw Error(fmt::format("unknown solver backend '{}' (valid: {})", s, solvers::backend_names()));
  for (int l : o.levels)
    if (l < 0 || l > 4) throw Error(fmt::format("mesh level {} outside 0..4", l));
  for (int n : o.ranks)
    if (n < 1 || n > 1024) throw Error(fmt::format("{} MPI processes per run: outside 1..1024", n));
  for (int n : o.ranks)
    for (const auto& s : solvers_list)
      for (const auto& b : solvers::backends())
        if (n > 1 && b.name == s && !b.distributed)
          throw Error(fmt::format("solver backend '{}' runs on one MPI process: leave it out of a sweep with --ranks {}",
                                  s, n));
  if (!o.sample.empty()) {
    parse_system_selection(o.sample);  // throws on a malformed item
    if (!known.count(o.path_solver))
      throw Error(fmt::format("unknown path backend '{}' (valid: {})", o.path_solver, solvers::backend_names()));
    for (const auto& [solver, level] : whole_runs(o)) {
      if (!known.count(solver))
        throw Error(fmt::format("--whole {}:{}: unknown solver backend (valid: {})", solver, level,
                                solvers::backend_names()));
      if (std::find(o.levels.begin(), o.levels.end(), level) == o.levels.end())
        throw Error(fmt::format("--whole {}:{}: level {} is not one of the sweep's --levels", solver, level, level));
    }
    for (int n : o.ranks)
      if (n != 1) throw Error("a sweep with --sample runs on one process (--ranks 1)");
  } else if (!o.whole.empty()) {
    throw Error("--whole names the whole runs beside a recorded sample: it needs --sample");
  }
  // PETSc options go to the children whose prefix they carry; one that matches no backend
  // of the sweep would be silently ignored, so it is an error.
  for (size_t k = 0; k < o.petsc_options.size(); ++k) {
    const std::string& opt = o.petsc_options[k];
    bool matches = false;
    for (const auto& s : solvers_list) matches |= opt.rfind("-" + solvers::options_prefix(s), 0) == 0;
    if (!matches) throw Error(fmt::format("PETSc option '{}' matches none of the backends of this sweep", opt));
  }
}

// The comment lines a new sweep's CSVs start with: how the sweep was made.
std::string sweep_header(const BenchOptions& o, const RunInfo& info, const ChildLimits& limits,
                         const std::vector<std::string>& solvers_list) {
  std::string header = format_run_info(info, "# ");
  header += fmt::format("# limits per run: {:.0f} s, {:.0f} MB resident\n", limits.seconds, limits.memory_mb);
  for (const auto& s : solvers_list)
    header += fmt::format("# backend {} options: {}\n", s, solvers::compact_options(s));
  for (const auto& opt : o.petsc_options) header += "# petsc option: " + opt + "\n";
  header += fmt::format("# MPI processes per run: {} (this machine: {} cores)\n", fmt::join(o.ranks, ", "),
                        std::thread::hardware_concurrency());
  header += "# newton forcing: " + (o.forcing.empty() ? std::string("as each scene sets it") : o.forcing) + "\n";
  header += "# newton rtol: as each scene sets it (newton.rtol; the runs' newton_rtol column)\n";
  header += "# krylov rtol: " +
            (o.krylov_rtol < 0 ? std::string("as each scene sets it (newton.krylov_rtol, else the backend's)")
                               : fmt::format("{:g}", o.krylov_rtol)) +
            "\n";
  header += "# gmres restart: as each scene sets it (newton.krylov_restart, else the backend's options), unless a "
            "petsc option above gives it\n";
  return header;
}

// The sweep's PETSc options that go to this backend (those with its prefix), space-joined.
std::string options_for(const BenchOptions& o, const std::string& solver) {
  std::vector<std::string> mine;
  for (const auto& option : o.petsc_options)
    if (option.rfind("-" + solvers::options_prefix(solver), 0) == 0) mine.push_back(option);
  return fmt::format("{}", fmt::join(mine, " "));
}

// The child's command line: `stiction solve` of the run into run_dir (continued from its
// checkpoint there when `continued`), with the sweep's settings, `extra` arguments and the
// PETSc options whose prefix is the run's backend.
std::vector<std::string> child_arguments(const BenchOptions& o, const BenchRun& run, const std::string& exe,
                                         const std::string& run_dir, bool continued,
                                         const std::vector<std::string>& extra = {}) {
  std::vector<std::string> argv{exe,        "solve",    run.scene,  "--level",   std::to_string(run.level),
                                "--solver", run.solver, continued ? "--restart" : "--out", run_dir, "--quiet",
                                "--no-vtu", "--metrics", run_dir + "/metrics.toml"};
  if (!o.forcing.empty()) argv.insert(argv.end(), {"--forcing", o.forcing});
  if (o.krylov_rtol >= 0) argv.insert(argv.end(), {"--krylov-rtol", fmt::format("{:g}", o.krylov_rtol)});
  if (o.quick) argv.push_back("--quick");
  argv.insert(argv.end(), extra.begin(), extra.end());
  std::istringstream words(options_for(o, run.solver));
  for (std::string w; words >> w;) argv.push_back(w);
  return argv;
}

// One step of a sweep: a whole run (the path run of a sample records its systems), or one
// backend's replay of a recorded sample.
struct Job {
  enum class Kind { Whole, Path, Sample } kind = Kind::Whole;
  BenchRun run;
  // The key the time-left estimate knows the job by: a replay is estimated from the same
  // backend's replays, never from its whole runs.
  BenchRun estimated() const {
    return kind == Kind::Sample ? BenchRun{run.scene, "sample:" + run.solver, run.level, run.processes} : run;
  }
};

// The sweep's jobs in order. Without a sample: scene x solver x level x processes, whole
// runs. With one: per level and scene, the path run, the extra whole runs at that level,
// then every backend's replay of the sample.
std::vector<Job> plan_jobs(const BenchOptions& o, const std::vector<std::string>& scenes,
                           const std::vector<std::string>& solvers_list) {
  std::vector<Job> jobs;
  for (int level : o.levels)
    for (const auto& scene : scenes) {
      if (o.sample.empty()) {
        for (const auto& solver : solvers_list)
          for (int processes : o.ranks) jobs.push_back({Job::Kind::Whole, {scene, solver, level, processes}});
        continue;
      }
      jobs.push_back({Job::Kind::Path, {scene, o.path_solver, level, 1}});
      for (const auto& [solver, whole_level] : whole_runs(o))
        if (whole_level == level && solver != o.path_solver) jobs.push_back({Job::Kind::Whole, {scene, solver, level, 1}});
      for (const auto& solver : solvers_list) jobs.push_back({Job::Kind::Sample, {scene, solver, level, 1}});
    }
  return jobs;
}

// The state a sweep carries from job to job.
struct Sweep {
  const BenchOptions& o;
  std::string out, exe, revision;
  ChildLimits limits;
  std::vector<BenchRun> estimated;  // every job, as the time-left estimate knows it
  FinishedRuns finished;
  std::set<std::string> done;       // runs.csv and samples.csv keys already there
};

std::string sample_key(const BenchRun& r) { return "sample|" + r.key(); }

// The row of runs.csv of a finished whole run (empty when there is none).
std::map<std::string, std::string> runs_row(const std::string& out, const BenchRun& run) {
  for (const auto& row : read_csv(out + "/runs.csv").rows)
    if (bench_run_of(row).key() == run.key()) return row;
  return {};
}

void run_whole(Sweep& sw, const Job& job, size_t position) {
  const BenchRun& run = job.run;
  const BenchOptions& o = sw.o;
  const std::string progress = fmt::format("bench [{}/{}] {} {} L{}{}{}", position + 1, sw.estimated.size(), run.scene,
                                           run.solver, run.level,
                                           run.processes > 1 ? fmt::format(" np{}", run.processes) : "",
                                           job.kind == Job::Kind::Path ? " (path, records the sample)" : "");
  const std::string run_dir = (fs::path(sw.out) / "runs" / run.id()).string();
  const std::optional<Interrupted> continued = o.resume ? interrupted_run(run, run_dir) : std::nullopt;
  std::error_code ec;
  if (!continued) {
    fs::remove_all(run_dir, ec);  // a run the sweep had started and not recorded: its own leftovers
    fs::create_directories(run_dir, ec);
  } else if (continued->ended) {
    fmt::print(stderr, "{}: had ended without its row; the row comes from its record\n", progress);
  } else {
    fmt::print(stderr, "{}: continued from its checkpoint after load step {}\n", progress, continued->last_step);
  }
  const std::vector<std::string> argv =
      child_arguments(o, run, sw.exe, run_dir, continued.has_value(),
                      job.kind == Job::Kind::Path ? record_arguments(sample_record_dir(sw.out, run.scene, run.level), o.sample)
                                                  : std::vector<std::string>{});
  int last_step = -1;
  double last_print = -1e9;
  const auto on_tick = [&](double t) {
    const int step = count_data_lines(run_dir + "/steps.csv");
    if (step != last_step || t - last_print > 30) {
      fmt::print(stderr, "{}: {} load steps done, {:.0f} s; {}\n", progress, step, t,
                 time_left(sw.estimated, position, t, sw.finished, step, o.time_limit_seconds));
      last_step = step;
      last_print = t;
    }
  };
  // The time limit holds for the whole run, its earlier segments included.
  ChildLimits run_limits = sw.limits;
  if (continued) run_limits.seconds = std::max(sw.limits.seconds - continued->wall_seconds, 1.0);
  ChildResult child;
  if (continued && continued->ended)
    child.exit_code = continued->converged ? 0 : 3;  // as the run's own exit: converged, or Newton failed
  else
    child = run_child(argv, run_dir + "/stdout.txt", run_dir + "/stderr.txt", run_limits, on_tick,
                      launcher_for(run.processes));
  const double wall = write_rows(sw.out, run, child, run_dir, options_for(o, run.solver), continued, sw.revision);
  const std::string status = solve_status(child, fs::exists(run_dir + "/metrics.toml"));
  if (status == "ok") sw.finished.add(run, wall, load_step_fractions(run_dir + "/steps.csv"));
  fmt::print(stderr, "{}: {} in {:.1f} s, peak {:.0f} MB\n", progress, status, wall, child.peak_rss_mb);
}

void run_sample(Sweep& sw, const Job& job, size_t position) {
  const BenchRun& run = job.run;
  const BenchOptions& o = sw.o;
  const std::string progress = fmt::format("bench [{}/{}] {} {} L{} (recorded sample)", position + 1,
                                           sw.estimated.size(), run.scene, run.solver, run.level);
  const std::string record_dir = sample_record_dir(sw.out, run.scene, run.level);
  const std::string run_dir = sample_run_dir(sw.out, run.scene, run.level, run.solver);
  const std::string samples_csv = sw.out + "/samples.csv";
  std::vector<std::string> recorded;
  try {
    recorded = recorded_system_dirs(record_dir);
  } catch (const Error&) {
  }
  if (recorded.empty()) {
    const std::string why = fmt::format("the path run ({}) recorded none of the systems {}", o.path_solver,
                                        fmt::join(o.sample, ","));
    append_durably(samples_csv, unrecorded_sample_row(run.scene, run.level, run.solver, why, sw.revision));
    fmt::print(stderr, "{}: no-record ({})\n", progress, why);
    return;
  }
  std::error_code ec;
  fs::remove_all(run_dir, ec);  // a replay the sweep had started and not recorded
  fs::create_directories(run_dir, ec);
  std::vector<std::string> argv = replay_arguments(sw.exe, record_dir, run.solver, run_dir);
  std::istringstream words(options_for(o, run.solver));
  for (std::string w; words >> w;) argv.push_back(w);
  double last_print = -1e9;
  const auto on_tick = [&](double t) {
    if (t - last_print < 30) return;
    fmt::print(stderr, "{}: {} of {} systems solved, {:.0f} s; {}\n", progress,
               count_data_lines(run_dir + "/replay.csv"), recorded.size(), t,
               time_left(sw.estimated, position, t, sw.finished, 0, o.time_limit_seconds));
    last_print = t;
  };
  const ChildResult child = run_child(argv, run_dir + "/stdout.txt", run_dir + "/stderr.txt", sw.limits, on_tick);
  const auto path_row = runs_row(sw.out, {run.scene, o.path_solver, run.level, 1});
  const std::string row = sample_row(run.scene, run.level, run.solver, run_dir, child, path_row,
                                     static_cast<int>(o.sample.size()), sw.revision);
  append_durably(samples_csv, row);
  sw.finished.add(job.estimated(), child.wall_seconds);
  const CsvTable parsed = parse_csv(std::string(kSampleColumns) + "\n" + row);
  fmt::print(stderr, "{}: {} in {:.1f} s, peak {:.0f} MB\n", progress, parsed.rows.front().at("status"),
             child.wall_seconds, child.peak_rss_mb);
}

// Opens runs.csv (and samples.csv for a sweep with a sample) and collects what an earlier,
// resumed sweep finished.
void open_tables(Sweep& sw, const RunInfo& info, const std::vector<std::string>& solvers_list) {
  const BenchOptions& o = sw.o;
  std::string header;  // of a new sweep (steps.csv and samples.csv get it too)
  const CsvTable previous = open_sweep_table(sw.out + "/runs.csv", kRunColumns, o.resume, info, [&] {
    header = sweep_header(o, info, sw.limits, solvers_list);
    return header;
  }, o.allow_other_revision);
  for (const auto& row : previous.rows) {
    const BenchRun run = bench_run_of(row);
    sw.done.insert(run.key());
    if (row.at("status") == "ok")
      sw.finished.add(run, std::strtod(row.at("wall_seconds").c_str(), nullptr),
                      load_step_fractions(run_directory(sw.out, row) + "/steps.csv"));
  }
  const std::string steps_csv = sw.out + "/steps.csv";
  if (!header.empty())
    append_durably(steps_csv, header + kStepColumns);
  else if (fs::exists(steps_csv))  // a resumed sweep of an older version: its lines get the new columns too
    upgrade_sweep_columns(steps_csv, kStepColumns);
  if (o.sample.empty()) return;
  const std::string samples_csv = sw.out + "/samples.csv";
  if (!fs::exists(samples_csv)) {
    append_durably(samples_csv, (header.empty() ? sweep_header(o, info, sw.limits, solvers_list) : header) +
                                    fmt::format("# sample: systems {} of each scene and level, recorded by {}\n",
                                                fmt::join(o.sample, ","), o.path_solver) +
                                    kSampleColumns);
    return;
  }
  for (const auto& row : upgrade_sweep_columns(samples_csv, kSampleColumns).rows) {
    const BenchRun run{row.at("scene"), row.at("solver"), static_cast<int>(number(row, "level")), 1};
    sw.done.insert(sample_key(run));
    sw.finished.add(Job{Job::Kind::Sample, run}.estimated(), 0);
  }
}

}  // namespace

void run_bench(const BenchOptions& o, const RunInfo& info) {
  std::vector<std::string> scenes = o.scenes, solvers_list = o.solvers;
  if (scenes.empty())
    for (const auto& [name, text] : builtin_scenes()) scenes.push_back(name);
  if (solvers_list.empty())
    for (const auto& b : solvers::backends()) solvers_list.push_back(b.name);
  check_sweep(o, scenes, solvers_list);

  Sweep sw{o, o.out_dir, "stiction", build_revision(), sweep_limits(o.time_limit_seconds, o.memory_limit_mb),
           {}, {}, {}};
  std::error_code ec;
  fs::create_directories(fs::path(sw.out) / "runs", ec);
  if (ec) throw Error(fmt::format("cannot create '{}': {}", sw.out, ec.message()));
  open_tables(sw, info, solvers_list);

  const std::vector<Job> jobs = plan_jobs(o, scenes, solvers_list);
  for (const auto& job : jobs) sw.estimated.push_back(job.estimated());
  for (size_t position = 0; position < jobs.size(); ++position) {
    const Job& job = jobs[position];
    const bool sample = job.kind == Job::Kind::Sample;
    if (sw.done.count(sample ? sample_key(job.run) : job.run.key())) {
      fmt::print(stderr, "bench [{}/{}] {} {} L{}{}: already in {}, skipped\n", position + 1, jobs.size(),
                 job.run.scene, job.run.solver, job.run.level, sample ? " (recorded sample)" : "",
                 sample ? "samples.csv" : "runs.csv");
      continue;
    }
    if (sample)
      run_sample(sw, job, position);
    else
      run_whole(sw, job, position);
    write_bench_report(sw.out);
  }
  write_bench_report(sw.out);
}

}  // namespace stiction::harness
