#pragma once
// How each backend's cost grows with the mesh, for one scene of a sweep: the time per
// linear solve and the peak memory against the Newton system's size (displacement,
// pressure and multiplier unknowns) on log-log axes, with the least-squares exponent p of
// cost ~ n^p per backend, and the Krylov iterations per Newton step against the level (with
// their growth across the levels, in a table of every scene).
// Drawn as SVG by gnuplot (Debian's gnuplot-nox, which the report scripts install), from a
// data file and a script written beside the report so that anyone can redraw or restyle
// them.
#include <map>
#include <string>
#include <vector>

#include "csv_table.hpp"

namespace stiction::harness {

void write_text_file(const std::string& path, const std::string& text);  // throws when it cannot
// Runs `gnuplot <stem>.gp` in dir; false (its output kept in <stem>.log) when gnuplot is
// missing or fails.
bool draw_with_gnuplot(const std::string& dir, const std::string& stem);

// Least-squares slope of log(y) against log(x) over the points with x, y > 0; 0 with fewer
// than two such points.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y);

// A published measurement drawn beside a sweep's (the paper's Tables 1-3): one solver at
// one size; 0 where the source gives no figure.
struct ReferencePoint {
  std::string label;
  double n = 0, seconds_per_solve = 0, peak_mb = 0;
};

// The markdown section for `scene` (exponents table and the plots) when the sweep holds
// finished runs of it at two or more levels; empty otherwise. Writes
// <scene>-growth.dat / .gp and, when gnuplot runs, <scene>-time-per-solve.svg,
// <scene>-peak-memory.svg and <scene>-krylov.svg into out_dir. `measured_on` names where
// the figures come from in the titles ("" for whole runs); `reference` points are drawn
// beside them on the time and memory plots.
std::string scaling_section(const CsvTable& runs, const std::string& scene, const std::string& out_dir,
                            const std::string& measured_on = "", const std::vector<ReferencePoint>& reference = {});

// Krylov iterations per Newton step of one backend at one mesh level, the PETSc options its
// run there was given beyond the backend's defaults, and the settings it ran with (those
// defaults with the options on top: run_settings.hpp; "" when its metrics are missing).
struct LevelKrylov {
  double per_newton_step = 0;
  std::string options;
  std::string settings;
};
using KrylovByLevel = std::map<int, LevelKrylov>;

// "L0: 47.4; L1: 58.5; L2: 85.3 (-opt 50)": each level's count, and the options of a level
// that ran with some.
std::string krylov_per_level_text(const KrylovByLevel& levels);

// The count's growth from the coarsest to the finest level among levels run with the same
// settings (levels whose settings are unknown: with the same options): "1.80"; "1.23 (L0 to
// L1)" when those are not all the levels; "—" when no two levels share them. Of several such
// sets, the one spanning the most levels (on a tie, one run without extra options). Other
// settings can change the Krylov method itself (a shorter GMRES restart at the finest level,
// say), and a growth across them would measure that change; the same settings reached once
// through the defaults and once through an option are the same method.
std::string krylov_growth_text(const KrylovByLevel& levels);

// The sweep's "Krylov iterations per Newton step across mesh levels": a row per scene and
// iterative backend with finished runs at two or more levels; empty when there is none.
// Each run's settings are read from its metrics.toml under out_dir.
std::string krylov_growth_section(const CsvTable& runs, const std::string& out_dir);

}  // namespace stiction::harness
