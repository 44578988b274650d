#include "paper_tables.hpp"

#include "bench_estimate.hpp"
#include "memory_breakdown.hpp"
#include "sweep_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>

namespace stiction::harness {

const std::map<std::string, std::string>& embedded_reference();  // generated

namespace {

using Row = std::map<std::string, std::string>;

bool ok(const Row& r) { return r.at("status") == "ok"; }

std::string fixed(double v, int digits) { return v > 0 ? fmt::format("{:.{}f}", v, digits) : "—"; }

std::string ratio(double reference, double value) {
  return reference > 0 && value > 0 ? fmt::format("{:.2f}", reference / value) : "—";
}

// "ours / paper (+x%)"
std::string beside(double ours, double paper) {
  if (ours <= 0) return fmt::format("— / {:.0f}", paper);
  return fmt::format("{:.0f} / {:.0f} ({:+.1f}%)", ours, paper, 100 * (ours / paper - 1));
}

const Row* find_run(const std::vector<Row>& rows, const std::string& scene, int level, const std::string& solver) {
  for (const auto& r : rows)
    if (r.at("scene") == scene && number(r, "level") == level && r.at("solver") == solver) return &r;
  return nullptr;
}

// A run's per-step table in a sweep directory.
std::string steps_path(const std::string& out_dir, const Row& r) {
  return run_directory(out_dir, r) + "/steps.csv";
}

// The last load step's force on the clamped top (x, y, z) of a finished run.
std::optional<std::array<double, 3>> top_force(const std::string& out_dir, const Row& r) {
  const CsvTable steps = read_csv(steps_path(out_dir, r));
  if (steps.rows.empty()) return std::nullopt;
  const Row& last = steps.rows.back();
  std::array<double, 3> f{};
  for (int k = 0; k < 3; ++k) {
    const auto it = last.find(fmt::format("reaction_block/top_{}", "xyz"[k]));
    if (it == last.end()) return std::nullopt;
    f[k] = std::strtod(it->second.c_str(), nullptr);
  }
  return f;
}

// The Newton tolerance a run stopped at: its newton_rtol column, or for a run recorded before
// that column existed its steps.csv header ("# solver: ...; newton atol A, rtol R, ...").
std::string newton_rtol(const std::string& out_dir, const Row& r) {
  if (const auto it = r.find("newton_rtol"); it != r.end() && !it->second.empty()) return it->second;
  std::ifstream steps(steps_path(out_dir, r));
  std::string line;
  while (std::getline(steps, line) && line.rfind('#', 0) == 0) {
    const size_t at = line.find(", rtol ");
    if (line.rfind("# solver:", 0) != 0 || at == std::string::npos) continue;
    const size_t from = at + 7;
    return line.substr(from, line.find(',', from) - from);
  }
  return "";
}

bool same_tolerance(const std::string& a, const std::string& b) {
  return !a.empty() && !b.empty() && std::strtod(a.c_str(), nullptr) == std::strtod(b.c_str(), nullptr);
}

std::string mesh_table(const std::vector<Row>& runs) {
  const CsvTable paper = parse_csv(embedded_reference().at("table1-meshes"));
  std::string md =
      "\n### Table 1: meshes (stiction / paper)\n\nFrom the runs of `block-strips`; levels are uniform refinements "
      "of level 0, as the paper's.\n\n| level | vertices | tetrahedra | u unknowns | multiplier unknowns |\n"
      "|---|---|---|---|---|\n";
  bool any = false;
  for (const auto& p : paper.rows) {
    const int level = static_cast<int>(number(p, "level"));
    const Row* ours = nullptr;
    for (const auto& r : runs)
      if (r.at("scene") == "block-strips" && number(r, "level") == level && number(r, "vertices") > 0) ours = &r;
    if (!ours) continue;
    any = true;
    md += fmt::format("| {} | {} | {} | {} | {} |\n", level, beside(number(*ours, "vertices"), number(p, "vertices")),
                      beside(number(*ours, "cells"), number(p, "tetrahedra")),
                      beside(number(*ours, "unknowns_u_l") + number(*ours, "unknowns_u_q"), number(p, "u_unknowns")),
                      beside(number(*ours, "multipliers"), number(p, "multiplier_unknowns")));
  }
  return any ? md : "";
}

std::string time_table(const std::vector<Row>& runs, const std::string& out_dir, int table, const std::string& scene,
                       bool sampled) {
  const CsvTable paper = parse_csv(embedded_reference().at("tables2-3-times"));
  std::vector<int> levels;
  for (const auto& r : runs)
    if (r.at("scene") == scene) {
      const int l = static_cast<int>(number(r, "level"));
      if (std::find(levels.begin(), levels.end(), l) == levels.end()) levels.push_back(l);
    }
  if (levels.empty()) return "";
  std::sort(levels.begin(), levels.end());
  std::string md = fmt::format(
      "\n### Table {}: `{}`{}\n\nRatios are lu-mumps / backend (stiction) and GlobalLU / Schur (paper): above 1 the "
      "iterative solver is faster or leaner. Newton iterations are summed over the 8 load steps; Newton rtol is the "
      "relative residual each load step stopped at. Force: the clamped top's reaction after the last step, relative "
      "difference to lu-mumps' (it should be at the Newton tolerance's level). The total ratio and the force are "
      "given only between runs of the same Newton tolerance; time per solve and memory do not depend on it. A run its "
      "time limit stopped after some linear solves gives its figures per solve over those, its peak memory as a lower "
      "bound (\"≥\") and no totals.\n\n| level | solver | status | total s | s / linear solve | peak MB | Newton its "
      "| Newton rtol | Krylov / solve | total ratio | s/solve ratio | memory ratio | force vs lu-mumps |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      table, scene, sampled ? ", whole runs (measured totals)" : "");
  for (int level : levels) {
    const Row* lu = find_run(runs, scene, level, "lu-mumps");
    const auto lu_force = lu && ok(*lu) ? top_force(out_dir, *lu) : std::nullopt;
    const std::string lu_rtol = lu ? newton_rtol(out_dir, *lu) : "";
    for (const auto& r : runs) {
      if (r.at("scene") != scene || number(r, "level") != level) continue;
      const std::string rtol = newton_rtol(out_dir, r);
      const bool done = ok(r), per_solve = done || stopped_with_solves(r);
      const bool per_solve_ref = per_solve && lu && ok(*lu), ref = done && per_solve_ref && same_tolerance(rtol, lu_rtol);
      std::string force = "—";
      if (const auto f = ref ? top_force(out_dir, r) : std::nullopt; f && lu_force) {
        double diff = 0, size = 0;
        for (int k = 0; k < 3; ++k) diff += std::pow((*f)[k] - (*lu_force)[k], 2), size += std::pow((*lu_force)[k], 2);
        force = size > 0 ? fmt::format("{:.1e}", std::sqrt(diff / size)) : "—";
      }
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", level, r.at("solver"),
                        run_status_text(r),
                        done ? fixed(number(r, "wall_seconds"), 1) : "—",
                        per_solve ? fixed(number(r, "seconds_per_linear_solve"), 3) : "—",
                        peak_memory_text(r),
                        done ? fixed(number(r, "newton_iterations"), 0) : "—",
                        rtol.empty() ? "—" : rtol,
                        per_solve ? fixed(number(r, "krylov_per_linear_solve"), 1) : "—",
                        ref ? ratio(number(*lu, "wall_seconds"), number(r, "wall_seconds")) : "—",
                        per_solve_ref ? ratio(number(*lu, "seconds_per_linear_solve"), number(r, "seconds_per_linear_solve"))
                                      : "—",
                        done && per_solve_ref ? ratio(number(*lu, "peak_rss_mb"), number(r, "peak_rss_mb")) : "—", force);
    }
    const Row *schur = nullptr, *global = nullptr;
    for (const auto& p : paper.rows)
      if (number(p, "table") == table && number(p, "level") == level)
        (p.at("solver") == "GlobalLU" ? global : schur) = &p;
    for (const Row* p : {schur, global}) {
      if (!p) continue;
      const bool has = number(*p, "total_seconds") > 0;
      const bool pair = has && global && number(*global, "total_seconds") > 0;
      md += fmt::format("| {} | paper {} | {} | {} | {} | {} | {} | — | — | {} | {} | {} | — |\n", level, p->at("solver"),
                        has ? "ok" : "out of memory", fixed(number(*p, "total_seconds"), 1),
                        fixed(number(*p, "seconds_per_linear_solve"), 3), fixed(number(*p, "memory_mb"), 0),
                        fixed(number(*p, "newton_iterations"), 0),
                        pair ? ratio(number(*global, "total_seconds"), number(*p, "total_seconds")) : "—",
                        pair ? ratio(number(*global, "seconds_per_linear_solve"), number(*p, "seconds_per_linear_solve"))
                             : "—",
                        pair ? ratio(number(*global, "memory_mb"), number(*p, "memory_mb")) : "—");
    }
  }
  return md;
}

// The fastest direct backend (one that factorises each system: lu-*) that solved the whole
// sample of `scene` at `level`: the reference of every ratio on the sample.
const Row* fastest_direct(const std::vector<Row>& samples, const std::string& scene, int level) {
  const Row* best = nullptr;
  for (const auto& r : samples)
    if (r.at("scene") == scene && number(r, "level") == level && ok(r) && r.at("solver").rfind("lu-", 0) == 0 &&
        (!best || number(r, "seconds_per_linear_solve") < number(*best, "seconds_per_linear_solve")))
      best = &r;
  return best;
}

}  // namespace

// Table 2 or 3 on the recorded sample (table 0: another scene, no paper rows): every
// backend on the same systems, beside the paper.
std::string sample_table(const CsvTable& samples, int table, const std::string& scene) {
  const CsvTable paper = parse_csv(embedded_reference().at("tables2-3-times"));
  std::vector<int> levels;
  for (const auto& r : samples.rows)
    if (r.at("scene") == scene) {
      const int l = static_cast<int>(number(r, "level"));
      if (std::find(levels.begin(), levels.end(), l) == levels.end()) levels.push_back(l);
    }
  if (levels.empty()) return "";
  std::sort(levels.begin(), levels.end());
  std::string sample_text;
  for (const auto& c : samples.comments)
    if (c.rfind("sample: ", 0) == 0) sample_text = c.substr(8);
  const std::string title =
      table ? fmt::format("Table {}: `{}`, every backend on the recorded sample", table, scene)
            : fmt::format("`{}`: every backend on the recorded sample", scene);
  std::string md = fmt::format(
      "\n### {}\n\nSample: {}. Each backend solved those same "
      "Newton systems in a process of its own. s / linear solve = set-up + solve, averaged over the sample; peak MB = "
      "that process's peak resident memory (the systems and the solver, without the mesh and the assembly of a whole "
      "run); residual = the largest ||b - A x|| / ||b|| of its answers, computed by the harness. Ratios are against "
      "the reference named in the ref column (the fastest direct backend that solved the whole sample at that level): "
      "above 1 the backend is faster or leaner. **Total s is projected**: the path run's wall time with its linear "
      "solves' time replaced by as many solves at this backend's s / linear solve (the same Newton path assumed; the "
      "whole runs' measured totals are in the next table). The paper's rows are its whole runs.\n\n"
      "| level | solver | status | s / linear solve | peak MB | Krylov / solve | residual | ref | s/solve ratio | "
      "memory ratio | total s (projected) | total ratio (projected) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      title, sample_text.empty() ? "see samples.csv" : sample_text, table ? " The paper's rows are its whole runs." : "");
  for (int level : levels) {
    const Row* ref = fastest_direct(samples.rows, scene, level);
    for (const auto& r : samples.rows) {
      if (r.at("scene") != scene || number(r, "level") != level) continue;
      const bool done = ok(r), with_ref = done && ref;
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", level, r.at("solver"),
                        r.at("detail").empty() ? r.at("status") : r.at("status") + ": " + r.at("detail"),
                        done ? fixed(number(r, "seconds_per_linear_solve"), 3) : "—",
                        fixed(number(r, "peak_rss_mb"), 0), done ? fixed(number(r, "krylov_per_solve"), 1) : "—",
                        done ? fmt::format("{:.1e}", number(r, "max_relative_residual")) : "—",
                        ref ? ref->at("solver") : "—",
                        with_ref ? ratio(number(*ref, "seconds_per_linear_solve"), number(r, "seconds_per_linear_solve"))
                                 : "—",
                        with_ref ? ratio(number(*ref, "peak_rss_mb"), number(r, "peak_rss_mb")) : "—",
                        fixed(number(r, "projected_total_seconds"), 1),
                        with_ref ? ratio(number(*ref, "projected_total_seconds"), number(r, "projected_total_seconds"))
                                 : "—");
    }
    const Row *schur = nullptr, *global = nullptr;
    for (const auto& p : paper.rows)
      if (table && number(p, "table") == table && number(p, "level") == level)
        (p.at("solver") == "GlobalLU" ? global : schur) = &p;
    for (const Row* p : {schur, global}) {
      if (!p) continue;
      const bool has = number(*p, "total_seconds") > 0;
      const bool pair = has && global && number(*global, "total_seconds") > 0;
      md += fmt::format("| {} | paper {} | {} | {} | {} | — | — | {} | {} | {} | {} (whole run) | {} |\n", level,
                        p->at("solver"), has ? "ok" : "out of memory", fixed(number(*p, "seconds_per_linear_solve"), 3),
                        fixed(number(*p, "memory_mb"), 0), pair ? "paper GlobalLU" : "—",
                        pair ? ratio(number(*global, "seconds_per_linear_solve"), number(*p, "seconds_per_linear_solve"))
                             : "—",
                        pair ? ratio(number(*global, "memory_mb"), number(*p, "memory_mb")) : "—",
                        fixed(number(*p, "total_seconds"), 1),
                        pair ? ratio(number(*global, "total_seconds"), number(*p, "total_seconds")) : "—");
    }
  }
  return md;
}

std::vector<ReferencePoint> paper_points(const std::string& scene) {
  const int table = scene == "block-strips" ? 2 : scene == "block-strips-mr" ? 3 : 0;
  if (!table) return {};
  const CsvTable meshes = parse_csv(embedded_reference().at("table1-meshes"));
  std::map<int, double> unknowns;  // the paper's Newton system: P2 displacements and multipliers
  for (const auto& m : meshes.rows)
    unknowns[static_cast<int>(number(m, "level"))] = number(m, "u_unknowns") + number(m, "multiplier_unknowns");
  std::vector<ReferencePoint> points;
  for (const auto& p : parse_csv(embedded_reference().at("tables2-3-times")).rows)
    if (number(p, "table") == table && number(p, "total_seconds") > 0)
      points.push_back({"paper " + p.at("solver"), unknowns[static_cast<int>(number(p, "level"))],
                        number(p, "seconds_per_linear_solve"), number(p, "memory_mb")});
  return points;
}

std::string paper_tables_section(const CsvTable& table, const CsvTable& samples, const std::string& out_dir) {
  const std::vector<Row>& runs = table.rows;
  bool any = false;
  for (const auto& r : runs) any |= r.at("scene") == "block-strips" || r.at("scene") == "block-strips-mr";
  if (!any) return "";
  const bool sampled = !samples.rows.empty();
  std::string md =
      "\n## The paper's tables (Lacasse & Fortin, Sec. 6.3)\n\nThe paper's figures: "
      "`reference/lacasse-fortin-block-strips/` (its README gives the source). Its hardware is not stated: compare "
      "ratios, not seconds.\n";
  md += mesh_table(runs);
  md += sample_table(samples, 2, "block-strips");
  md += time_table(runs, out_dir, 2, "block-strips", sampled);
  md += sample_table(samples, 3, "block-strips-mr");
  md += time_table(runs, out_dir, 3, "block-strips-mr", sampled);
  md += memory_breakdown_table(runs, out_dir, {"block-strips", "block-strips-mr"});
  // Drawn by scripts/render-contact-states.py (scripts/paper-tables.sh) after the sweep.
  std::vector<std::string> pictures;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(out_dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("contact-states-", 0) == 0 && e.path().extension() == ".png") pictures.push_back(name);
  }
  std::sort(pictures.begin(), pictures.end());
  if (!pictures.empty()) {
    md += "\n### Contact states at the last load step (the paper's Figures 11 and 12)\n\nEvery slave node coloured "
          "inactive / stick / slip, and the groove-wall nodes that touch; drawn from `runs/<run>/contact.csv` by "
          "`scripts/render-contact-states.py`.\n";
    for (const auto& p : pictures) md += fmt::format("\n![{}]({})\n", p.substr(0, p.size() - 4), p);
  }
  return md;
}

}  // namespace stiction::harness
