#pragma once
// How each backend's cost grows with the mesh, for one scene of a sweep: the time per
// linear solve and the peak memory against the Newton system's size (displacement,
// pressure and multiplier unknowns) on log-log axes, with the least-squares exponent p of
// cost ~ n^p per backend, and the Krylov iterations per Newton step against the level.
// Drawn as SVG by gnuplot (Debian's gnuplot-nox, which the report scripts install), from a
// data file and a script written beside the report so that anyone can redraw or restyle
// them.
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

// The markdown section for `scene` (exponents table and the plots) when the sweep holds
// finished runs of it at two or more levels; empty otherwise. Writes
// <scene>-growth.dat / .gp and, when gnuplot runs, <scene>-time-per-solve.svg,
// <scene>-peak-memory.svg and <scene>-krylov.svg into out_dir.
std::string scaling_section(const CsvTable& runs, const std::string& scene, const std::string& out_dir);

}  // namespace stiction::harness
