#include "tradeoff_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "csv_table.hpp"
#include "scaling_plots.hpp"

namespace stiction::harness {

const char* const kTradeoffColumns =
    "scene,level,id,solver,forcing,newton_rtol,krylov_rtol,knob,default,status,reason,newton_iterations,linear_solves,"
    "krylov_iterations,wall_seconds,linear_seconds,peak_rss_mb,error_u_l2,error_u_h1,error_contact_force,"
    "error_peak_pressure,state_changes,error_hertz_a,error_hertz_p0,error_stick_zone,error_patch_pressure,detail";

namespace {

using Row = std::map<std::string, std::string>;

bool measured(const Row& r) { return r.at("status") == "ok" && !r.at("error_u_h1").empty(); }

std::string command_of(const Row& r) {
  std::string c = fmt::format("stiction solve {} --level {} --solver {}", r.at("scene"), r.at("level"), r.at("solver"));
  if (!r.at("forcing").empty() && r.at("forcing") != "fixed") c += " --forcing " + r.at("forcing");
  if (!r.at("newton_rtol").empty()) c += " --newton-rtol " + r.at("newton_rtol");
  if (!r.at("krylov_rtol").empty()) c += " --krylov-rtol " + r.at("krylov_rtol");
  if (const std::string& knob = r.at("knob"); !knob.empty())
    c += " -" + knob.substr(0, knob.find('=')) + " " + knob.substr(knob.find('=') + 1);
  return c;
}

// A missing column (a table written before the column existed) shows as unmeasured.
std::string cell(const Row& r, const std::string& key) {
  const auto it = r.find(key);
  return it == r.end() || it->second.empty() ? "—" : it->second;
}

// The measured runs no other measured run beats on both wall time and displacement error
// (H1), fastest first.
std::vector<const Row*> pareto_front(const std::vector<const Row*>& runs) {
  std::vector<const Row*> sorted = runs, front;
  std::sort(sorted.begin(), sorted.end(), [](const Row* a, const Row* b) {
    const double ta = number(*a, "wall_seconds"), tb = number(*b, "wall_seconds");
    return ta != tb ? ta < tb : number(*a, "error_u_h1") < number(*b, "error_u_h1");
  });
  double best = INFINITY;
  for (const Row* r : sorted)
    if (number(*r, "error_u_h1") < best) {
      front.push_back(r);
      best = number(*r, "error_u_h1");
    }
  return front;
}

// The Pareto plot: one point series per backend, the front as a staircase. Returns the
// markdown line that shows it, or says why it was not drawn.
std::string plot(const std::string& out_dir, const std::vector<const Row*>& runs, const std::vector<const Row*>& front) {
  std::map<std::string, std::vector<const Row*>> by_solver;
  for (const Row* r : runs) by_solver[r->at("solver")].push_back(r);
  // An error of exactly zero (the reference's own answer) sits at the bottom of the log axis.
  auto error = [](const Row* r) { return std::max(number(*r, "error_u_h1"), 1e-16); };
  std::string data, series;
  int block = 0;
  for (const auto& [solver, rows] : by_solver) {
    data += fmt::format("# {}: wall_seconds error_u_h1\n", solver);
    for (const Row* r : rows) data += fmt::format("{} {:.6e}\n", r->at("wall_seconds"), error(r));
    data += "\n\n";
    series += fmt::format("{}data index {} using 1:2 with points pt 7 ps 1.2 title '{}'", block ? ", \\\n     " : "plot ",
                          block, solver);
    ++block;
  }
  data += "# Pareto front\n";
  for (const Row* r : front) data += fmt::format("{} {:.6e}\n", r->at("wall_seconds"), error(r));
  series += fmt::format(", \\\n     data index {} using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front'", block);
  const std::string stem = "tradeoff";
  write_text_file(out_dir + "/" + stem + ".dat", data);
  write_text_file(out_dir + "/" + stem + ".gp",
                  fmt::format("# Redraw with: gnuplot {0}.gp (in this directory)\n"
                              "data = '{0}.dat'\n"
                              "set terminal svg size 720,480 dynamic font 'sans,12'\n"
                              "set output '{0}.svg'\nset key right top\nset grid\nset logscale xy\n"
                              "set xlabel 'wall time of the run (s)'\n"
                              "set ylabel 'displacement error against the reference (H1, relative)'\n"
                              "set title 'speed against accuracy'\n{1}\n",
                              stem, series));
  if (!draw_with_gnuplot(out_dir, stem))
    return "Plot not drawn: gnuplot failed or is missing (`tradeoff.log`; `scripts/ensure-gnuplot.sh` installs "
           "it); `tradeoff.gp` draws it.\n";
  return "![wall time against displacement error](tradeoff.svg)\n";
}

}  // namespace

void write_tradeoff_report(const std::string& out_dir) {
  const CsvTable table = read_csv(out_dir + "/tradeoff.csv");
  std::string md = "# Speed against accuracy";
  if (!table.rows.empty())
    md += fmt::format(": {} level {}", table.rows.front().at("scene"), table.rows.front().at("level"));
  md += "\n\nHow it was made:\n\n```\n";
  for (const auto& c : table.comments) md += c + "\n";
  md += "```\n\n"
        "Accuracy is each run's final state against the reference's (first row), on the same mesh: the "
        "displacement error in L2 and in the H1 seminorm, the contact force (every pair's multiplier integral), "
        "the largest contact pressure, each relative to the reference, and the slave nodes whose contact state "
        "differs. Where the scene models an analytic solution, the final state against it, the reference's own "
        "included: on a Hertz scene (reference/hertz) the fitted contact half-width and peak pressure against "
        "Hertz's; on Cattaneo-Mindlin (reference/cattaneo-mindlin) the stick-zone edge's distance from "
        "Mindlin's over the contact half-width; on the patch test (reference/contact-patch) the largest "
        "deviation of a node's pressure from the uniform one. Cost is the run's wall time (its own process), the time in linear solves (set-up and solve) "
        "and its peak resident memory.\n\n## Runs\n\n"
        "| setting | status | Newton | Krylov | wall s | linear s | peak MB | error u L2 | error u H1 | contact "
        "force | peak pressure | states changed | Hertz a | Hertz p0 | stick zone | patch pressure |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  // Runs on the reference's mesh (the first row) enter the front; the coarser meshes' rows
  // are compared with it across meshes, which bounds the displacement error from below only.
  const std::string level = table.rows.empty() ? "" : table.rows.front().at("level");
  std::vector<const Row*> runs, coarser;
  for (const auto& r : table.rows) {
    if (r.at("level") != level) {  // a finer --discretisation reference is reported with it
      if (std::stoi(r.at("level")) < std::stoi(level)) coarser.push_back(&r);
      continue;
    }
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r.at("id"),
                      r.at("status") == "ok" ? "ok" : r.at("status") + " (" + r.at("reason") + ")",
                      r.at("newton_iterations"), r.at("krylov_iterations"), r.at("wall_seconds"),
                      r.at("linear_seconds"), r.at("peak_rss_mb"), cell(r, "error_u_l2"), cell(r, "error_u_h1"),
                      cell(r, "error_contact_force"), cell(r, "error_peak_pressure"), cell(r, "state_changes"),
                      cell(r, "error_hertz_a"), cell(r, "error_hertz_p0"), cell(r, "error_stick_zone"),
                      cell(r, "error_patch_pressure"));
    if (measured(r)) runs.push_back(&r);
  }
  const CsvTable levels = read_csv(out_dir + "/discretisation.csv");
  double mesh_h1 = 0;  // the discretisation's change of |u|_H1 (0: not measured)
  if (!levels.rows.empty()) {
    const Row& d = levels.rows.front();
    mesh_h1 = number(d, "displacement_h1");
    md += fmt::format("\n## What the mesh changes\n\nThe reference at level {} against level {}: |u|_H1 {}, "
                      "||u||_L2 {}, contact force {}, peak pressure {} (relative differences; the norms' "
                      "difference bounds the norm of the difference from below). A setting whose error against "
                      "the reference lies well below these buys accuracy the mesh does not have.\n",
                      d.at("level"), d.at("fine_level"), d.at("displacement_h1"), d.at("displacement_l2"),
                      cell(d, "contact_force"), cell(d, "peak_pressure"));
  }
  if (!coarser.empty()) {
    md += fmt::format("\n## The mesh as a knob\n\nEach backend at its defaults on coarser meshes, against the "
                      "reference at level {}: the differences of |u|_H1 and ||u||_L2 (lower bounds of the errors), of "
                      "the contact force and of the peak pressure, relative; the analytic comparison where the "
                      "scene models one. These rows are not on the Pareto front, whose errors are on one mesh.\n\n"
                      "| setting | level | status | Newton | Krylov | wall s | peak MB | u H1 | u L2 | contact "
                      "force | peak pressure | Hertz a | Hertz p0 | stick zone | patch pressure |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
                      level);
    for (const Row* r : coarser)
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", r->at("id"),
                        r->at("level"), r->at("status") == "ok" ? "ok" : r->at("status") + " (" + r->at("reason") + ")",
                        r->at("newton_iterations"), r->at("krylov_iterations"), r->at("wall_seconds"),
                        r->at("peak_rss_mb"), cell(*r, "error_u_h1"), cell(*r, "error_u_l2"),
                        cell(*r, "error_contact_force"), cell(*r, "error_peak_pressure"), cell(*r, "error_hertz_a"),
                        cell(*r, "error_hertz_p0"), cell(*r, "error_stick_zone"), cell(*r, "error_patch_pressure"));
  }
  if (!runs.empty()) {
    const auto front = pareto_front(runs);
    md += "\n## Pareto front (wall time against the displacement error in H1)\n\n"
          "| setting | wall s | error u H1 | contact force | command |\n|---|---|---|---|---|\n";
    for (const Row* r : front)
      md += fmt::format("| {} | {} | {} | {} | `{}` |\n", r->at("id"), r->at("wall_seconds"), r->at("error_u_h1"),
                        cell(*r, "error_contact_force"), command_of(*r));
    md += "\n" + plot(out_dir, runs, front);
    md += "\n## Recommendations\n\n";
    for (double target : {1e-2, 1e-4, 1e-6, 1e-8}) {
      const Row* best = nullptr;
      for (const Row* r : front)
        if (number(*r, "error_u_h1") <= target) {
          best = r;
          break;  // the front is sorted fastest first
        }
      if (!best) {
        md += fmt::format("* Displacement error (H1) at most {:g}: no run reached it.\n", target);
        continue;
      }
      md += fmt::format("* Displacement error (H1) at most {:g}: `{}`, {} s (error {})", target, command_of(*best),
                        best->at("wall_seconds"), best->at("error_u_h1"));
      if (mesh_h1 > 0 && target < 0.1 * mesh_h1)
        md += fmt::format(" (ten times finer than the mesh's own {:.1e})", mesh_h1);
      const auto defaults = std::find_if(table.rows.begin(), table.rows.end(), [&](const Row& r) {
        return r.at("solver") == best->at("solver") && r.at("default") == "1" && r.at("status") == "ok" &&
               r.at("level") == level;
      });
      if (defaults != table.rows.end() && &*defaults != best) {
        const double speedup = number(*defaults, "wall_seconds") / number(*best, "wall_seconds");
        md += fmt::format(": {:.1f}x {} {}'s defaults ({} s, error {})", speedup >= 1 ? speedup : 1 / speedup,
                          speedup >= 1 ? "faster than" : "the time of", best->at("solver"),
                          defaults->at("wall_seconds"), cell(*defaults, "error_u_h1"));
      }
      md += ".\n";
    }
  }
  write_text_file(out_dir + "/report.md", md);
}

}  // namespace stiction::harness
