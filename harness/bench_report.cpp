#include "bench_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <tuple>

#include "bench_estimate.hpp"
#include "common/error.hpp"
#include "csv_table.hpp"
#include "ksp_solver.hpp"
#include "paper_tables.hpp"
#include "scaling_plots.hpp"
#include "sweep_table.hpp"

namespace stiction::harness {

namespace {

using Row = std::map<std::string, std::string>;

bool finished(const Row& r) { return r.at("status") == "ok"; }

// "—" for a run that produced no number, as in the paper's tables.
std::string cell(const Row& r, const char* key, const char* format) {
  if (!finished(r) && r.at("status") != "newton-failed") return "—";
  return fmt::format(fmt::runtime(format), number(r, key));
}

// A figure per linear solve: measured also by a run its time limit stopped after some solves.
std::string per_solve_cell(const Row& r, const char* key, const char* format) {
  return stopped_with_solves(r) ? fmt::format(fmt::runtime(format), number(r, key)) : cell(r, key, format);
}

std::string ratio(double reference, double value) {
  if (reference <= 0 || value <= 0) return "—";
  return fmt::format("{:.2f}", reference / value);
}

// MPI processes of a run (1 for an older sweep's rows, which have no such column).
int processes_of(const Row& r) { return bench_run_of(r).processes; }

// Strong scaling: each (scene, level, backend) run on several process counts, against its
// one-process run. Assembly per Newton iteration, time per linear solve, and the peak
// memory per process and in all.
std::string strong_scaling_section(const CsvTable& runs) {
  std::map<std::tuple<std::string, int, std::string>, std::map<int, const Row*>> groups;
  bool several = false;
  for (const auto& r : runs.rows) {
    groups[{r.at("scene"), static_cast<int>(number(r, "level")), r.at("solver")}][processes_of(r)] = &r;
    several |= processes_of(r) > 1;
  }
  if (!several) return {};
  std::string md =
      "\n## Strong scaling\n\nThe same run on more MPI processes (`--ranks`), against one process: speed-up = "
      "one-process time / this time. Assembly s / Newton = assembly seconds per Newton iteration; peak MB / process "
      "= the largest process's peak resident memory, total MB = the sum over processes.\n\n"
      "| scene | level | solver | processes | status | total s | s / linear solve | speed-up / solve | assembly s / "
      "Newton | speed-up / assembly | Krylov / solve | peak MB / process | total MB |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [key, by_processes] : groups) {
    if (by_processes.size() < 2 && by_processes.begin()->first == 1) continue;
    const Row* one = by_processes.count(1) && finished(*by_processes.at(1)) ? by_processes.at(1) : nullptr;
    auto assembly = [](const Row& r) {
      const double newton = number(r, "newton_iterations");
      return newton > 0 ? number(r, "assembly_seconds") / newton : 0.0;
    };
    for (const auto& [processes, row] : by_processes) {
      const Row& r = *row;
      const bool ok = finished(r);
      const double per_process = number(r, "peak_rss_mb_per_process") > 0 ? number(r, "peak_rss_mb_per_process")
                                                                          : number(r, "peak_rss_mb");
      md += fmt::format(
          "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", std::get<0>(key), std::get<1>(key),
          std::get<2>(key), processes, r.at("status"), cell(r, "wall_seconds", "{:.1f}"),
          ok ? fmt::format("{:.3f}", number(r, "seconds_per_linear_solve")) : "—",
          ok && one ? ratio(number(*one, "seconds_per_linear_solve"), number(r, "seconds_per_linear_solve")) : "—",
          ok ? fmt::format("{:.3f}", assembly(r)) : "—", ok && one ? ratio(assembly(*one), assembly(r)) : "—",
          cell(r, "krylov_per_linear_solve", "{:.1f}"), ok ? fmt::format("{:.0f}", per_process) : "—",
          ok ? fmt::format("{:.0f}", number(r, "peak_rss_mb")) : "—");
    }
  }
  return md;
}

// The assembly per Newton iteration split into the contact constraints' part and the rest
// (the volume's), for the finished runs that recorded the split and have contact.
std::string assembly_split_section(const CsvTable& runs) {
  std::string rows;
  for (const auto& r : runs.rows) {
    const double newton = number(r, "newton_iterations"), contact = number(r, "contact_assembly_seconds");
    if (!finished(r) || newton <= 0 || contact <= 0) continue;
    const double volume = number(r, "assembly_seconds") - contact;
    rows += fmt::format("| {} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {} |\n", r.at("scene"), r.at("level"),
                        r.at("solver"), number(r, "assembly_seconds") / newton, contact / newton, volume / newton,
                        volume > 0 ? fmt::format("{:.2f}", contact / volume) : "—");
  }
  if (rows.empty()) return {};
  return "\n## Assembly per Newton iteration: contact and volume\n\nSeconds per Newton iteration. Contact = the "
         "contact constraints' part of the assembly (their residual and Jacobian, the bordered matrix and the "
         "multiplier surface's blocks); volume = the rest (the bodies' internal forces and tangent, loads, the "
         "Dirichlet lifting). Below 1 in the last column, contact costs less than the volume of the same mesh.\n\n"
         "| scene | level | solver | assembly s / Newton | contact | volume | contact / volume |\n"
         "|---|---|---|---|---|---|---|\n" +
         rows;
}

// A sweep's sample rows in the shape of runs.csv's, for the growth plots: the unknowns
// column of a sample is the whole system's already.
CsvTable samples_as_runs(const CsvTable& samples) {
  CsvTable runs = samples;
  for (auto& r : runs.rows) {
    r["multipliers"] = "0";
    r["krylov_per_linear_solve"] = r["krylov_per_solve"];
  }
  return runs;
}

// "Rows by revision" when a resumed sweep's rows came from binaries of several revisions.
std::string revisions_text(const CsvTable& runs, const CsvTable& samples) {
  std::map<std::string, int> count;
  for (const CsvTable* t : {&runs, &samples})
    for (const auto& r : t->rows)
      if (const auto it = r.find("revision"); it != r.end() && !it->second.empty()) ++count[it->second];
  if (count.size() < 2) return "";
  std::string text = "\n**Rows from several revisions** (the `revision` column of runs.csv and samples.csv): ";
  for (const auto& [revision, n] : count) text += fmt::format("{} rows from {}; ", n, revision);
  return text.substr(0, text.size() - 2) + ".\n";
}

}  // namespace

void write_bench_report(const std::string& out_dir) {
  const CsvTable all_runs = read_csv(out_dir + "/runs.csv");
  const CsvTable samples = read_csv(out_dir + "/samples.csv");
  // The tables, ratios and plots below compare backends on one process; runs on several
  // are compared with their one-process run in the strong-scaling section.
  CsvTable runs = all_runs;
  runs.rows.clear();
  for (const auto& r : all_runs.rows)
    if (processes_of(r) == 1) runs.rows.push_back(r);
  std::string md = "# stiction benchmark report\n\n## How it was made\n\n";
  for (const auto& c : runs.comments) md += "- " + c + "\n";
  md += "\nRaw data: `runs.csv` (one row per run), `steps.csv` (one row per linear solve), `runs/<run>/` (the "
        "backend's PETSc view in `solver.txt`, per-step CSV, stderr). Rebuild this page with `stiction report "
        "<dir>`.\n\nColumns: unknowns = the Newton system's (displacement, pressure and multipliers); total s = wall time of the run's process; s / linear solve = (set-up + Krylov solve) "
        "averaged over the linear solves that converged (\"—\" when none did: a factorisation refused for memory is no solve); peak MB = the run's peak resident memory (its own process); Krylov / "
        "solve = Krylov iterations per Newton step. Ratios are lu-mumps / backend on the same scene and level: above "
        "1 the backend is faster or leaner. \"—\": the run produced no figure (see status). A run its time limit "
        "stopped after some linear solves gives its figures per solve over those (its peak memory as a lower bound, "
        "\"≥\"), but no totals.\n";

  std::vector<std::string> scenes;
  std::set<std::string> solvers_seen;
  for (const auto& r : runs.rows) {
    if (std::find(scenes.begin(), scenes.end(), r.at("scene")) == scenes.end()) scenes.push_back(r.at("scene"));
    solvers_seen.insert(r.at("solver"));
  }
  md += revisions_text(all_runs, samples);
  md += paper_tables_section(runs, samples, out_dir);
  for (const auto& scene : scenes) {
    md += fmt::format("\n## {}{}\n\n| level | solver | status | unknowns | total s | s / linear solve | peak MB | Newton its "
                      "| linear solves | Krylov / solve | time/solve ratio | memory ratio |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                      scene, samples.rows.empty() ? "" : ": whole runs");
    std::vector<Row> rows;
    for (const auto& r : runs.rows)
      if (r.at("scene") == scene) rows.push_back(r);
    std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return number(a, "level") < number(b, "level"); });
    for (const auto& r : rows) {
      const Row* ref = nullptr;
      for (const auto& q : rows)
        if (q.at("solver") == "lu-mumps" && q.at("level") == r.at("level") && finished(q)) ref = &q;
      const bool ok = finished(r), per_solve = ok || stopped_with_solves(r);
      md += fmt::format("| {} | {} | {} | {:.0f} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.at("level"), r.at("solver"),
                        run_status_text(r), number(r, "unknowns") + number(r, "multipliers"),
                        cell(r, "wall_seconds", "{:.1f}"),
                        number(r, "seconds_per_linear_solve") > 0 ? per_solve_cell(r, "seconds_per_linear_solve", "{:.3f}") : "—",
                        peak_memory_text(r), cell(r, "newton_iterations", "{:.0f}"), per_solve_cell(r, "linear_solves", "{:.0f}"),
                        per_solve_cell(r, "krylov_per_linear_solve", "{:.1f}"),
                        per_solve && ref ? ratio(number(*ref, "seconds_per_linear_solve"), number(r, "seconds_per_linear_solve")) : "—",
                        ok && ref ? ratio(number(*ref, "peak_rss_mb"), number(r, "peak_rss_mb")) : "—");
    }
    const bool paper_scene = scene == "block-strips" || scene == "block-strips-mr";
    bool sampled = false;
    for (const auto& r : samples.rows) sampled |= r.at("scene") == scene;
    if (sampled && !paper_scene) md += sample_table(samples, 0, scene);
    md += sampled ? scaling_section(samples_as_runs(samples), scene, out_dir, "recorded sample", paper_points(scene))
                  : scaling_section(runs, scene, out_dir, "", paper_points(scene));
  }

  md += strong_scaling_section(all_runs);
  md += assembly_split_section(runs);

  md += krylov_growth_section(runs, out_dir);

  md += "\n## Backend options\n\nDefaults from `solvers/options/<name>.opts` (keys under the backend's prefix); "
        "options given on the command line, if any, are listed under How it was made.\n";
  for (const auto& s : solvers_seen) {
    const std::string opts = solvers::default_options(s);
    md += fmt::format("\n### {}\n\n```\n{}```\n", s, opts.empty() ? "(none)\n" : opts);
  }
  const std::string tmp = out_dir + "/report.md.tmp";
  {
    std::ofstream f(tmp);
    f << md;
    if (!f) throw Error(fmt::format("cannot write '{}'", tmp));
  }
  std::rename(tmp.c_str(), (out_dir + "/report.md").c_str());
}

}  // namespace stiction::harness
