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

namespace stiction::harness {

namespace fs = std::filesystem;

namespace {

const char* kRunColumns =
    "scene,level,solver,processes,status,converged,reason,unknowns,unknowns_u_l,unknowns_u_q,unknowns_p,multipliers,vertices,"
    "cells,load_steps,"
    "load_steps_completed,newton_iterations,linear_solves,krylov_iterations,krylov_per_linear_solve,wall_seconds,"
    "assembly_seconds,contact_assembly_seconds,setup_seconds,solve_seconds,seconds_per_linear_solve,peak_rss_mb,peak_rss_mb_per_process,mumps_memory_mb,"
    "mumps_factor_fraction,amg_operator_complexity,krylov_rtol,mumps_ordering,newton_rtol,newton_forcing,petsc_options,"
    "detail";
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
                  const std::string& petsc_options, const std::optional<Interrupted>& continued) {
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
      "{:.1f},{:.1f},{:.0f},{},{:.3f},{},{},{},{},{},{}",
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
      m["newton_forcing"].value<std::string>().value_or(""), csv_field(petsc_options), csv_field(detail));
  if (!figures.steps_csv.empty()) append_durably(out + "/steps.csv", figures.steps_csv);
  append_durably(out + "/runs.csv", row);
  return wall;
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
// checkpoint there when `continued`), with the sweep's settings and the PETSc options whose
// prefix is the run's backend.
std::vector<std::string> child_arguments(const BenchOptions& o, const BenchRun& run, const std::string& exe,
                                         const std::string& run_dir, bool continued) {
  std::vector<std::string> argv{exe,        "solve",    run.scene,  "--level",   std::to_string(run.level),
                                "--solver", run.solver, continued ? "--restart" : "--out", run_dir, "--quiet",
                                "--no-vtu", "--metrics", run_dir + "/metrics.toml"};
  if (!o.forcing.empty()) argv.insert(argv.end(), {"--forcing", o.forcing});
  if (o.krylov_rtol >= 0) argv.insert(argv.end(), {"--krylov-rtol", fmt::format("{:g}", o.krylov_rtol)});
  if (o.quick) argv.push_back("--quick");
  std::istringstream words(options_for(o, run.solver));
  for (std::string w; words >> w;) argv.push_back(w);
  return argv;
}

}  // namespace

void run_bench(const BenchOptions& o, const RunInfo& info) {
  std::vector<std::string> scenes = o.scenes, solvers_list = o.solvers;
  if (scenes.empty())
    for (const auto& [name, text] : builtin_scenes()) scenes.push_back(name);
  if (solvers_list.empty())
    for (const auto& b : solvers::backends()) solvers_list.push_back(b.name);
  check_sweep(o, scenes, solvers_list);

  const std::string out = o.out_dir;
  std::error_code ec;
  fs::create_directories(fs::path(out) / "runs", ec);
  if (ec) throw Error(fmt::format("cannot create '{}': {}", out, ec.message()));
  const std::string runs_csv = out + "/runs.csv";
  std::set<std::string> done;
  FinishedRuns finished_runs;  // for the time-left estimate
  const ChildLimits limits = sweep_limits(o.time_limit_seconds, o.memory_limit_mb);
  std::string header;  // of a new sweep (steps.csv gets it too)
  const CsvTable previous = open_sweep_table(runs_csv, kRunColumns, o.resume, info, [&] {
    header = sweep_header(o, info, limits, solvers_list);
    return header;
  });
  for (const auto& row : previous.rows) {
    const std::string processes = row.at("processes").empty() ? "1" : row.at("processes");  // an older sweep's rows
    const std::string key = fmt::format("{}|{}|{}|{}", row.at("scene"), row.at("level"), row.at("solver"), processes);
    done.insert(key);
    if (row.at("status") == "ok")
      finished_runs.add({row.at("scene"), row.at("solver"), std::stoi(row.at("level")), std::stoi(processes)},
                        std::strtod(row.at("wall_seconds").c_str(), nullptr),
                        load_step_fractions(run_directory(out, row) + "/steps.csv"));
  }
  const std::string steps_csv = out + "/steps.csv";
  if (!header.empty())
    append_durably(steps_csv, header + kStepColumns);
  else if (fs::exists(steps_csv))  // a resumed sweep of an older version: its lines get the new columns too
    upgrade_sweep_columns(steps_csv, kStepColumns);

  std::vector<BenchRun> runs;
  for (int level : o.levels)
    for (const auto& scene : scenes)
      for (const auto& solver : solvers_list)
        for (int processes : o.ranks) runs.push_back({scene, solver, level, processes});
  const std::string exe = self_executable();
  int index = 0;
  for (const BenchRun& run : runs) {
    const size_t position = index;
    ++index;
    const std::string on = run.processes > 1 ? fmt::format(" np{}", run.processes) : "";
    if (done.count(run.key())) {
      fmt::print(stderr, "bench [{}/{}] {} {} L{}{}: already in runs.csv, skipped\n", index, runs.size(), run.scene,
                 run.solver, run.level, on);
      continue;
    }
    const std::string run_dir = (fs::path(out) / "runs" / run.id()).string();
    const std::optional<Interrupted> continued = o.resume ? interrupted_run(run, run_dir) : std::nullopt;
    if (!continued) {
      fs::remove_all(run_dir, ec);
      fs::create_directories(run_dir, ec);
    } else if (continued->ended) {
      fmt::print(stderr, "bench [{}/{}] {} {} L{}{}: had ended without its row; the row comes from its record\n",
                 index, runs.size(), run.scene, run.solver, run.level, on);
    } else {
      fmt::print(stderr, "bench [{}/{}] {} {} L{}{}: continued from its checkpoint after load step {}\n", index,
                 runs.size(), run.scene, run.solver, run.level, on, continued->last_step);
    }
    const std::vector<std::string> argv = child_arguments(o, run, exe, run_dir, continued.has_value());
    int last_step = -1;
    double last_print = -1e9;
    const auto on_tick = [&](double t) {
      const int step = count_data_lines(run_dir + "/steps.csv");
      if (step != last_step || t - last_print > 30) {
        fmt::print(stderr, "bench [{}/{}] {} {} L{}{}: {} load steps done, {:.0f} s; {}\n", index, runs.size(),
                   run.scene, run.solver, run.level, on, step, t,
                   time_left(runs, position, t, finished_runs, step, o.time_limit_seconds));
        last_step = step;
        last_print = t;
      }
    };
    // The time limit holds for the whole run, its earlier segments included.
    ChildLimits run_limits = limits;
    if (continued) run_limits.seconds = std::max(limits.seconds - continued->wall_seconds, 1.0);
    ChildResult child;
    if (continued && continued->ended)
      child.exit_code = continued->converged ? 0 : 3;  // as the run's own exit: converged, or Newton failed
    else
      child = run_child(argv, run_dir + "/stdout.txt", run_dir + "/stderr.txt", run_limits, on_tick,
                        launcher_for(run.processes));
    const double wall = write_rows(out, run, child, run_dir, options_for(o, run.solver), continued);
    const std::string status = solve_status(child, fs::exists(run_dir + "/metrics.toml"));
    if (status == "ok") finished_runs.add(run, wall, load_step_fractions(run_dir + "/steps.csv"));
    fmt::print(stderr, "bench [{}/{}] {} {} L{}{}: {} in {:.1f} s, peak {:.0f} MB\n", index, runs.size(), run.scene,
               run.solver, run.level, on, status, wall, child.peak_rss_mb);
    write_bench_report(out);
  }
  write_bench_report(out);
}

}  // namespace stiction::harness
