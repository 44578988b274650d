#include "atlas_report.hpp"

#include <fmt/format.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "csv_table.hpp"
#include "scaling_plots.hpp"

namespace stiction::harness {

namespace fs = std::filesystem;

const char* const kAtlasColumns =
    "scene,level,axis,value,solver,status,reason,exit_code,newton_iterations,krylov_iterations,state_changes,"
    "wall_seconds,peak_rss_mb,nan_in_output,violation,detail";

std::string cell_id(const std::string& key, const std::string& value, const std::string& solver) {
  std::string id = key + "=" + value + "-" + solver;
  for (char& c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '=' && c != '-' && c != '.') c = '_';
  return id;
}

namespace {

using Row = std::map<std::string, std::string>;
// (value, backend) -> its row; for a pair's grid, (first value, second value) -> one backend's row.
using CellMap = std::map<std::pair<std::string, std::string>, const Row*>;

// The cell's metrics.toml (none when its run wrote none).
std::optional<toml::table> cell_metrics(const std::string& out_dir, const Row& r) {
  try {
    return toml::parse_file(out_dir + "/runs/" + cell_id(r.at("axis"), r.at("value"), r.at("solver")) +
                            "/metrics.toml");
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Why a cell failed, from its run's metrics.toml: the Newton verdict's detail and the last
// linear solve (its reason, Krylov iterations, the residual reduction reached against the
// one asked, the AMG operator complexity, GMRES's conditioning estimate and MUMPS's pivoting
// where there are).
std::string why_it_failed(const std::string& out_dir, const Row& r) {
  std::string why = r.at("detail").empty() ? r.at("reason") : r.at("reason") + ": " + r.at("detail");
  const std::optional<toml::table> metrics = cell_metrics(out_dir, r);
  if (!metrics) return why;
  const toml::array* solves = (*metrics)["linear_solve"].as_array();
  if (!solves || solves->empty() || !solves->back().as_table()) return why;
  const toml::table& last = *solves->back().as_table();
  why += fmt::format("; last linear solve {}", last["reason"].value<std::string>().value_or("?"));
  const double b = last["initial_residual"].value<double>().value_or(0),
               res = last["final_residual"].value<double>().value_or(0);
  if (const auto its = last["krylov_iterations"].value<int64_t>(); its && *its > 0) {
    why += fmt::format(" after {} Krylov iterations", *its);
    if (b > 0) why += fmt::format(", residual reduced to {:.1e}", res / b);
    if (const auto rtol = last["ksp_rtol"].value<double>()) why += fmt::format(" (asked {:g})", *rtol);
  }
  if (const auto c = last["amg_operator_complexity"].value<double>()) why += fmt::format(", AMG operator complexity {:.2f}", *c);
  const auto sigma_max = last["sigma_max_estimate"].value<double>(), sigma_min = last["sigma_min_estimate"].value<double>();
  if (sigma_max && sigma_min)
    why += fmt::format(", preconditioned operator's condition estimate {:.1e} (singular values {:.1e} / {:.1e} from "
                       "GMRES's last cycle)",
                       *sigma_max / *sigma_min, *sigma_max, *sigma_min);
  for (const std::string prefix : {"", "ll_"}) {
    const auto delayed = last[prefix + "mumps_delayed_pivots"].value<double>(),
               off_diagonal = last[prefix + "mumps_off_diagonal_pivots"].value<double>();
    if (delayed && off_diagonal)
      why += fmt::format(", MUMPS{} delayed {:.0f} pivots and chose {:.0f} off the diagonal", prefix.empty() ? "" : " (A_ll)",
                         *delayed, *off_diagonal);
  }
  return why;
}

// The largest conditioning estimate of the preconditioned operator over the cell's linear
// solves (GMRES backends, solvers/ksp_solver.hpp), or none.
std::optional<double> largest_condition_estimate(const std::string& out_dir, const Row& r) {
  const std::optional<toml::table> metrics = cell_metrics(out_dir, r);
  const toml::array* solves = metrics ? (*metrics)["linear_solve"].as_array() : nullptr;
  if (!solves) return std::nullopt;
  std::optional<double> largest;
  for (const auto& solve : *solves)
    if (const auto* t = solve.as_table())
      if (const auto c = (*t)["condition_estimate"].value<double>()) largest = std::max(largest.value_or(0.0), *c);
  return largest;
}

// A markdown table of rows x columns, each cell text(row, column) ("—" when it has none).
std::string grid_table(const std::string& corner, const std::vector<std::string>& rows,
                       const std::vector<std::string>& columns,
                       const std::function<std::string(const std::string&, const std::string&)>& text) {
  std::string md = "| " + corner + " |";
  for (const auto& c : columns) md += " " + c + " |";
  md += "\n|---|";
  for (size_t k = 0; k < columns.size(); ++k) md += "---|";
  md += "\n";
  for (const auto& r : rows) {
    md += "| " + r + " |";
    for (const auto& c : columns) md += " " + text(r, c) + " |";
    md += "\n";
  }
  return md;
}

// Per cell of a table (rows x columns, the cells keyed (row, column)), the largest
// conditioning estimate (empty when no cell has one).
std::string conditioning_table(const std::string& out_dir, const std::string& corner,
                               const std::vector<std::string>& rows, const std::vector<std::string>& columns,
                               const CellMap& cells) {
  bool any = false;
  const std::string table = grid_table(corner, rows, columns, [&](const std::string& r, const std::string& c) {
    const auto it = cells.find({r, c});
    const auto estimate = it == cells.end() ? std::nullopt : largest_condition_estimate(out_dir, *it->second);
    any = any || estimate.has_value();
    return estimate ? fmt::format("{:.1e}", *estimate) : std::string("—");
  });
  if (!any) return {};
  return "\nLargest conditioning estimate of the preconditioned operator over each cell's linear solves "
         "(sigma_max / sigma_min from GMRES's Hessenberg matrix, its last restart cycle; — for a direct backend "
         "or a run without the figure):\n\n" +
         table;
}

// Load increments the cell's run failed and retried with a smaller increment (the rows of
// its steps.csv that did not converge; 0 when the run wrote none).
int failed_increments(const std::string& out_dir, const Row& r) {
  const std::string steps = out_dir + "/runs/" + cell_id(r.at("axis"), r.at("value"), r.at("solver")) + "/steps.csv";
  if (!fs::exists(steps)) return 0;
  int failed = 0;
  for (const auto& row : read_csv(steps).rows) failed += number(row, "converged") == 0;
  return failed;
}

std::string cell_text(const std::string& out_dir, const Row& r) {
  std::string text = r.at("status") == "ok"
                         ? fmt::format("{} N / {} K", r.at("newton_iterations"), r.at("krylov_iterations"))
                         : r.at("reason");
  if (const int cut = failed_increments(out_dir, r); cut > 0 && r.at("status") == "ok")
    text += fmt::format(", {} cut", cut);
  if (!r.at("violation").empty()) text += " **" + r.at("violation") + "**";
  return text;
}

// Heat map of one axis: a square per (value, backend), coloured by Newton iterations when
// the cell converged, a cross where it did not. Returns the markdown that shows it.
std::string heat_map(const std::string& out_dir, const std::string& axis, const std::vector<std::string>& values,
                     const std::vector<std::string>& solvers, const CellMap& cells,
                     int index) {
  std::string ok, failed;
  for (size_t i = 0; i < values.size(); ++i)
    for (size_t j = 0; j < solvers.size(); ++j) {
      const auto it = cells.find({values[i], solvers[j]});
      if (it == cells.end()) continue;
      if (it->second->at("status") == "ok") ok += fmt::format("{} {} {}\n", i, j, it->second->at("newton_iterations"));
      else failed += fmt::format("{} {}\n", i, j);
    }
  std::string xtics, ytics;
  for (size_t i = 0; i < values.size(); ++i) xtics += fmt::format("{}'{}' {}", i ? ", " : "", values[i], i);
  for (size_t j = 0; j < solvers.size(); ++j) ytics += fmt::format("{}'{}' {}", j ? ", " : "", solvers[j], j);
  const std::string stem = fmt::format("atlas-axis-{}", index);
  // gnuplot needs at least one point per data block: a point outside the range stands in.
  write_text_file(out_dir + "/" + stem + ".dat", "# converged: value_index solver_index newton_iterations\n" +
                                                      (ok.empty() ? "-10 -10 0\n" : ok) + "\n\n# failed\n" +
                                                      (failed.empty() ? "-10 -10\n" : failed));
  write_text_file(out_dir + "/" + stem + ".gp",
                  fmt::format("# Redraw with: gnuplot {0}.gp (in this directory)\n"
                              "set terminal svg size {1},{2} dynamic font 'sans,12'\nset output '{0}.svg'\n"
                              "set title \"{3}\" noenhanced\nset xrange [-0.5:{4}.5]\nset yrange [-0.5:{5}.5]\n"
                              "set xtics ({6}) noenhanced\nset ytics ({7}) noenhanced\nset cblabel 'Newton iterations'\n"
                              "set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')\nset key below\n"
                              "plot '{0}.dat' index 0 using 1:2:3 with points pt 5 ps 5 lc palette title 'converged', \\\n"
                              "     '{0}.dat' index 1 using 1:2 with points pt 2 ps 4 lw 3 lc rgb 'black' title 'failed'\n",
                              stem, 200 + 90 * values.size(), 160 + 60 * solvers.size(), axis, values.size() - 1,
                              solvers.size() - 1, xtics, ytics));
  if (!draw_with_gnuplot(out_dir, stem))
    return fmt::format("Heat map not drawn: gnuplot failed or is missing (`{0}.log`); `{0}.gp` draws it.\n", stem);
  return fmt::format("![{}]({}.svg)\n", axis, stem);
}

// One key swept alone: value x backend.
std::string axis_section(const std::string& out_dir, const std::string& axis, const std::vector<std::string>& values,
                         const std::vector<std::string>& solvers, const CellMap& cells, int& index) {
  std::string md = fmt::format("\n## {}\n\n", axis);
  md += grid_table(axis, values, solvers, [&](const std::string& v, const std::string& s) {
    const auto it = cells.find({v, s});
    return it == cells.end() ? std::string("—") : cell_text(out_dir, *it->second);
  });
  md += conditioning_table(out_dir, "value", values, solvers, cells);
  return md + "\n" + heat_map(out_dir, axis, values, solvers, cells, index++);
}

std::pair<std::string, std::string> split_pair(const std::string& text) {
  const auto at = text.find(kPairSeparator);
  if (at == std::string::npos) return {text, ""};
  return {text.substr(0, at), text.substr(at + std::string(kPairSeparator).size())};
}

// Two keys swept together: per backend, the first key's values x the second's.
std::string pair_section(const std::string& out_dir, const std::string& axis, const std::vector<std::string>& values,
                         const std::vector<std::string>& solvers, const CellMap& cells, int& index) {
  const auto [first_key, second_key] = split_pair(axis);
  std::vector<std::string> firsts, seconds;
  for (const auto& v : values) {
    const auto [a, b] = split_pair(v);
    if (std::find(firsts.begin(), firsts.end(), a) == firsts.end()) firsts.push_back(a);
    if (std::find(seconds.begin(), seconds.end(), b) == seconds.end()) seconds.push_back(b);
  }
  std::string md = fmt::format("\n## {} (together)\n", axis);
  for (const auto& s : solvers) {
    CellMap grid;  // (first value, second value) -> the backend's cell
    for (const auto& [key, row] : cells)
      if (key.second == s) grid[split_pair(key.first)] = row;
    md += fmt::format("\n### {}: {} (rows) x {} (columns)\n\n", s, first_key, second_key);
    md += grid_table(first_key + " \\ " + second_key, firsts, seconds, [&](const std::string& a, const std::string& b) {
      const auto it = grid.find({a, b});
      return it == grid.end() ? std::string("—") : cell_text(out_dir, *it->second);
    });
    md += conditioning_table(out_dir, first_key + " \\ " + second_key, firsts, seconds, grid);
    md += "\n" + heat_map(out_dir, s + ": " + axis, firsts, seconds, grid, index++);
  }
  return md;
}

}  // namespace

void write_atlas_report(const std::string& out_dir) {
  const CsvTable table = read_csv(out_dir + "/atlas.csv");
  std::string md = "# Stability atlas";
  if (!table.rows.empty()) md += ": " + table.rows.front().at("scene");
  md += "\n\nHow it was made:\n\n```\n";
  for (const auto& c : table.comments) md += c + "\n";
  md += "```\n\nEach cell is the base scene with one key changed (`stiction solve SCENE --set KEY=VALUE`), run "
        "in its own process. A converged cell shows its Newton (N) and Krylov (K) iterations and, when some load "
        "increments failed and were retried smaller, how many (cut); a failed one its named reason. What must "
        "hold in every cell: it ends converged or with a named reason (exit code 3), never a crash, a hang (the "
        "time limit) or a NaN in its output.\n\n## Cells that broke what must hold\n\n";
  std::vector<std::string> axes;
  std::map<std::string, std::vector<std::string>> values, solvers;
  std::map<std::string, CellMap> cells;
  int violations = 0;
  for (const auto& r : table.rows) {
    const std::string& axis = r.at("axis");
    if (!values.count(axis)) axes.push_back(axis);
    auto& v = values[axis];
    if (std::find(v.begin(), v.end(), r.at("value")) == v.end()) v.push_back(r.at("value"));
    auto& s = solvers[axis];
    if (std::find(s.begin(), s.end(), r.at("solver")) == s.end()) s.push_back(r.at("solver"));
    cells[axis][{r.at("value"), r.at("solver")}] = &r;
    if (!r.at("violation").empty()) {
      ++violations;
      md += fmt::format("* {} = {}, {}: **{}** ({})\n", axis, r.at("value"), r.at("solver"), r.at("violation"),
                        r.at("detail"));
    }
  }
  if (!violations) md += "None: every cell converged or named why it did not.\n";
  std::string failures;
  for (const auto& r : table.rows)
    if (r.at("status") != "ok")
      failures += fmt::format("* {} = {}, {}: {}\n", r.at("axis"), r.at("value"), r.at("solver"), why_it_failed(out_dir, r));
  if (!failures.empty()) md += "\n## Why cells failed\n\n" + failures;
  int index = 0;
  for (const auto& axis : axes)
    md += axis.find(kPairSeparator) == std::string::npos
              ? axis_section(out_dir, axis, values[axis], solvers[axis], cells[axis], index)
              : pair_section(out_dir, axis, values[axis], solvers[axis], cells[axis], index);
  write_text_file(out_dir + "/report.md", md);
}

}  // namespace stiction::harness
