#include "scaling_plots.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>

#include "common/error.hpp"
#include "run_settings.hpp"
#include "sweep_table.hpp"

namespace stiction::harness {

namespace {

struct Point {
  int level;
  double n, seconds_per_solve, peak_mb, krylov;
  std::string options;
};

}  // namespace

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f) throw Error(fmt::format("cannot write '{}'", path));
}

bool draw_with_gnuplot(const std::string& dir, const std::string& stem) {
  const int rc = std::system(fmt::format("cd '{}' && gnuplot '{}.gp' > '{}.log' 2>&1", dir, stem, stem).c_str());
  if (rc == 0) std::remove((dir + "/" + stem + ".log").c_str());
  return rc == 0;
}

double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> lx, ly;
  for (size_t k = 0; k < x.size() && k < y.size(); ++k)
    if (x[k] > 0 && y[k] > 0) lx.push_back(std::log(x[k])), ly.push_back(std::log(y[k]));
  if (lx.size() < 2) return 0;
  double mx = 0, my = 0;
  for (size_t k = 0; k < lx.size(); ++k) mx += lx[k], my += ly[k];
  mx /= lx.size(), my /= ly.size();
  double sxy = 0, sxx = 0;
  for (size_t k = 0; k < lx.size(); ++k) sxy += (lx[k] - mx) * (ly[k] - my), sxx += (lx[k] - mx) * (lx[k] - mx);
  return sxx > 0 ? sxy / sxx : 0;
}

std::string scaling_section(const CsvTable& runs, const std::string& scene, const std::string& out_dir,
                            const std::string& measured_on, const std::vector<ReferencePoint>& reference) {
  std::map<std::string, std::map<int, Point>> by_solver;  // solver -> level -> point
  for (const auto& r : runs.rows) {
    if (r.at("scene") != scene || r.at("status") != "ok") continue;
    const int level = static_cast<int>(number(r, "level"));
    by_solver[r.at("solver")][level] = {level, number(r, "unknowns") + number(r, "multipliers"),
                                        number(r, "seconds_per_linear_solve"), number(r, "peak_rss_mb"),
                                        number(r, "krylov_per_linear_solve"), extra_petsc_options(r)};
  }
  for (auto it = by_solver.begin(); it != by_solver.end();)
    it = it->second.size() < 2 ? by_solver.erase(it) : std::next(it);
  if (by_solver.empty()) return "";

  std::string md = fmt::format(
      "\n### {}: growth with the mesh{}\n\nLeast-squares exponent p of cost ~ n^p over the levels (n: unknowns of the "
      "Newton system, multipliers included). A level run with PETSc options beyond the backend's defaults names "
      "them in the last column.\n\n| solver | levels | p (s / linear solve) | p (peak memory) | Krylov / "
      "solve per level |\n|---|---|---|---|---|\n",
      scene, measured_on.empty() ? "" : " (" + measured_on + ")");
  std::string data, time_plot, memory_plot, krylov_plot;
  int block = 0;
  for (const auto& [solver, points] : by_solver) {
    std::vector<double> n, t, m;
    std::string levels;
    KrylovByLevel krylov;
    data += fmt::format("# {}\n# n s_per_solve peak_mb level krylov_per_solve\n", solver);
    for (const auto& [level, p] : points) {
      n.push_back(p.n), t.push_back(p.seconds_per_solve), m.push_back(p.peak_mb);
      krylov[level] = {p.krylov, p.options};  // shown with its options; growth is krylov_growth_section's
      levels += fmt::format("{}{}", levels.empty() ? "" : ", ", level);
      data += fmt::format("{:.0f} {:.6g} {:.6g} {} {:.3f}\n", p.n, p.seconds_per_solve, p.peak_mb, level, p.krylov);
    }
    data += "\n\n";
    const double pt = log_log_slope(n, t), pm = log_log_slope(n, m);
    md += fmt::format("| {} | {} | {:.2f} | {:.2f} | {} |\n", solver, levels, pt, pm, krylov_per_level_text(krylov));
    const std::string sep = block ? ", \\\n     " : "plot ";
    time_plot += fmt::format("{}data index {} using 1:2 with linespoints pt 7 lw 2 title '{} (p = {:.2f})'", sep, block, solver, pt);
    memory_plot += fmt::format("{}data index {} using 1:3 with linespoints pt 7 lw 2 title '{} (p = {:.2f})'", sep, block, solver, pm);
    krylov_plot += fmt::format("{}data index {} using 4:5 with linespoints pt 7 lw 2 title '{}'", sep, block, solver);
    ++block;
  }
  // Reference points by label, one data block each, drawn as points without lines.
  std::map<std::string, std::vector<const ReferencePoint*>> by_label;
  for (const auto& p : reference) by_label[p.label].push_back(&p);
  for (const auto& [label, points] : by_label) {
    data += fmt::format("# {}\n# n s_per_solve peak_mb\n", label);
    for (const auto* p : points)
      data += fmt::format("{:.0f} {} {}\n", p->n, p->seconds_per_solve > 0 ? fmt::format("{:.6g}", p->seconds_per_solve) : "NaN",
                          p->peak_mb > 0 ? fmt::format("{:.6g}", p->peak_mb) : "NaN");
    data += "\n\n";
    time_plot += fmt::format(", \\\n     data index {} using 1:2 with points pt 6 ps 1.5 lw 2 title '{}'", block, label);
    memory_plot += fmt::format(", \\\n     data index {} using 1:3 with points pt 6 ps 1.5 lw 2 title '{}'", block, label);
    ++block;
  }
  const std::string on = measured_on.empty() ? "" : " (" + measured_on + ")";
  const std::string stem = scene + "-growth";
  write_text_file(out_dir + "/" + stem + ".dat", data);
  const std::string script = fmt::format(
      "# Redraw with: gnuplot {0}.gp (in this directory)\n"
      "data = '{0}.dat'\n"
      "set terminal svg size 720,480 dynamic font 'sans,12'\n"
      "set key left top\nset grid\n"
      "set logscale xy\nset xlabel 'unknowns of the Newton system'\n"
      "set output '{1}-time-per-solve.svg'\nset ylabel 's / linear solve (set-up + Krylov)'\n"
      "set title '{1}: time per linear solve{5}'\n{2}\n"
      "set output '{1}-peak-memory.svg'\nset ylabel 'peak resident memory (MB)'\n"
      "set title '{1}: peak memory{5}'\n{3}\n"
      "unset logscale\nset xlabel 'mesh level'\nset xtics 1\nset ylabel 'Krylov iterations per Newton step'\n"
      "set output '{1}-krylov.svg'\nset title '{1}: Krylov iterations per Newton step{5}'\n{4}\n",
      stem, scene, time_plot, memory_plot, krylov_plot, on);
  write_text_file(out_dir + "/" + stem + ".gp", script);
  if (!draw_with_gnuplot(out_dir, stem))
    return md + fmt::format("\nPlots not drawn: gnuplot failed or is missing (see `{}.log`; "
                            "`scripts/ensure-gnuplot.sh` installs it); `{}.gp` draws them.\n",
                            stem, stem);
  return md + fmt::format("\n![time per linear solve]({0}-time-per-solve.svg) ![peak memory]({0}-peak-memory.svg) "
                          "![Krylov iterations]({0}-krylov.svg)\n",
                          scene);
}

std::string krylov_per_level_text(const KrylovByLevel& levels) {
  std::string text;
  for (const auto& [level, k] : levels) {
    text += fmt::format("{}L{}: {:.1f}", text.empty() ? "" : "; ", level, k.per_newton_step);
    if (!k.options.empty()) text += " (" + k.options + ")";
  }
  return text;
}

std::string krylov_growth_text(const KrylovByLevel& levels) {
  std::map<std::string, KrylovByLevel> by_settings;
  for (const auto& [level, k] : levels)
    by_settings[k.settings.empty() ? "options: " + k.options : "settings: " + k.settings][level] = k;
  auto without_options = [](const KrylovByLevel& group) {
    for (const auto& [level, k] : group)
      if (!k.options.empty()) return false;
    return true;
  };
  const KrylovByLevel* widest = nullptr;
  for (const auto& [key, group] : by_settings)
    if (group.size() >= 2 && (!widest || group.size() > widest->size() ||
                              (group.size() == widest->size() && without_options(group) && !without_options(*widest))))
      widest = &group;
  if (!widest) return "—";
  const auto& [first, coarsest] = *widest->begin();
  const auto& [last, finest] = *widest->rbegin();
  const std::string growth = fmt::format("{:.2f}", finest.per_newton_step / coarsest.per_newton_step);
  return widest->size() == levels.size() ? growth : fmt::format("{} (L{} to L{})", growth, first, last);
}

std::string krylov_growth_section(const CsvTable& runs, const std::string& out_dir) {
  std::map<std::pair<std::string, std::string>, KrylovByLevel> series;  // (scene, solver) -> levels
  for (const auto& r : runs.rows)
    if (r.at("status") == "ok" && number(r, "krylov_per_linear_solve") > 1)
      series[{r.at("scene"), r.at("solver")}][static_cast<int>(number(r, "level"))] = {
          number(r, "krylov_per_linear_solve"), extra_petsc_options(r), run_backend_settings(out_dir, r)};
  std::string rows;
  for (const auto& [key, levels] : series)
    if (levels.size() >= 2)
      rows += fmt::format("| {} | {} | {} | {} |\n", key.first, key.second, krylov_per_level_text(levels),
                          krylov_growth_text(levels));
  if (rows.empty()) return "";
  return "\n## Krylov iterations per Newton step across mesh levels\n\nGrowth: finest / coarsest level among "
         "the levels whose runs had the same PETSc settings (the backend's defaults of the version that ran each, "
         "with the options the sweep gave on top; options beyond the defaults are named beside their level).\n\n| scene | solver | per level | growth |\n"
         "|---|---|---|---|\n" +
         rows;
}

}  // namespace stiction::harness
