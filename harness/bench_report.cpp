#include "bench_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

#include "common/error.hpp"
#include "csv_table.hpp"
#include "ksp_solver.hpp"
#include "paper_tables.hpp"
#include "scaling_plots.hpp"

namespace stiction::harness {

namespace {

using Row = std::map<std::string, std::string>;

bool finished(const Row& r) { return r.at("status") == "ok"; }

// "—" for a run that produced no number, as in the paper's tables.
std::string cell(const Row& r, const char* key, const char* format) {
  if (!finished(r) && r.at("status") != "newton-failed") return "—";
  return fmt::format(fmt::runtime(format), number(r, key));
}

std::string ratio(double reference, double value) {
  if (reference <= 0 || value <= 0) return "—";
  return fmt::format("{:.2f}", reference / value);
}

}  // namespace

void write_bench_report(const std::string& out_dir) {
  const CsvTable runs = read_csv(out_dir + "/runs.csv");
  std::string md = "# stiction benchmark report\n\n## How it was made\n\n";
  for (const auto& c : runs.comments) md += "- " + c + "\n";
  md += "\nRaw data: `runs.csv` (one row per run), `steps.csv` (one row per linear solve), `runs/<run>/` (the "
        "backend's PETSc view in `solver.txt`, per-step CSV, stderr). Rebuild this page with `stiction report "
        "<dir>`.\n\nColumns: unknowns = the Newton system's (displacement, pressure and multipliers); total s = wall time of the run's process; s / linear solve = (set-up + Krylov solve) "
        "averaged over the linear solves that converged (\"—\" when none did: a factorisation refused for memory is no solve); peak MB = the run's peak resident memory (its own process); Krylov / "
        "solve = Krylov iterations per Newton step. Ratios are lu-mumps / backend on the same scene and level: above "
        "1 the backend is faster or leaner. \"—\": the run produced no figure (see status).\n";

  std::vector<std::string> scenes;
  std::set<std::string> solvers_seen;
  for (const auto& r : runs.rows) {
    if (std::find(scenes.begin(), scenes.end(), r.at("scene")) == scenes.end()) scenes.push_back(r.at("scene"));
    solvers_seen.insert(r.at("solver"));
  }
  md += paper_tables_section(runs, out_dir);
  for (const auto& scene : scenes) {
    md += fmt::format("\n## {}\n\n| level | solver | status | unknowns | total s | s / linear solve | peak MB | Newton its "
                      "| linear solves | Krylov / solve | time/solve ratio | memory ratio |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                      scene);
    std::vector<Row> rows;
    for (const auto& r : runs.rows)
      if (r.at("scene") == scene) rows.push_back(r);
    std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return number(a, "level") < number(b, "level"); });
    for (const auto& r : rows) {
      const Row* ref = nullptr;
      for (const auto& q : rows)
        if (q.at("solver") == "lu-mumps" && q.at("level") == r.at("level") && finished(q)) ref = &q;
      const bool ok = finished(r);
      md += fmt::format("| {} | {} | {} | {:.0f} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.at("level"), r.at("solver"),
                        r.at("status") == "ok" ? "ok" : r.at("status") + (r.at("detail").empty() ? "" : ": " + r.at("detail")),
                        number(r, "unknowns") + number(r, "multipliers"), cell(r, "wall_seconds", "{:.1f}"), number(r, "seconds_per_linear_solve") > 0 ? cell(r, "seconds_per_linear_solve", "{:.3f}") : "—",
                        ok ? fmt::format("{:.0f}", number(r, "peak_rss_mb")) : "—", cell(r, "newton_iterations", "{:.0f}"),
                        cell(r, "linear_solves", "{:.0f}"), cell(r, "krylov_per_linear_solve", "{:.1f}"),
                        ok && ref ? ratio(number(*ref, "seconds_per_linear_solve"), number(r, "seconds_per_linear_solve")) : "—",
                        ok && ref ? ratio(number(*ref, "peak_rss_mb"), number(r, "peak_rss_mb")) : "—");
    }
    md += scaling_section(runs, scene, out_dir);
  }

  // Growth of Krylov iterations per Newton step with the mesh level (iterative backends).
  std::string growth;
  for (const auto& scene : scenes)
    for (const auto& solver : solvers_seen) {
      std::map<int, double> by_level;
      for (const auto& r : runs.rows)
        if (r.at("scene") == scene && r.at("solver") == solver && finished(r) && number(r, "krylov_per_linear_solve") > 1)
          by_level[static_cast<int>(number(r, "level"))] = number(r, "krylov_per_linear_solve");
      if (by_level.size() < 2) continue;
      std::string cells;
      for (const auto& [level, k] : by_level) cells += fmt::format("L{}: {:.1f}; ", level, k);
      growth += fmt::format("| {} | {} | {} | {:.2f} |\n", scene, solver, cells,
                            by_level.rbegin()->second / by_level.begin()->second);
    }
  if (!growth.empty())
    md += "\n## Krylov iterations per Newton step across mesh levels\n\n| scene | solver | per level | growth "
          "(finest / coarsest) |\n|---|---|---|---|\n" + growth;

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
