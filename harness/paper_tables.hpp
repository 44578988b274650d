#pragma once
// The paper's Tables 1-3 (reference/lacasse-fortin-block-strips/, compiled in) beside a
// sweep's runs of the block with strips: Table 1 (mesh counts) from any run of
// `block-strips`, Table 2 from `block-strips` (linear), Table 3 from `block-strips-mr`
// (Mooney-Rivlin), with each backend's ratios to lu-mumps next to the paper's GlobalLU /
// Schur ratios, and the converged forces of every backend against lu-mumps' (the same
// Newton tolerance must give the same answer).
#include <string>

#include <vector>

#include "csv_table.hpp"
#include "scaling_plots.hpp"

namespace stiction::harness {

// The markdown section, empty when the sweep holds no run of either scene. out_dir holds
// the sweep (runs/<run>/steps.csv gives the forces).
// With a recorded sample (samples.csv rows; empty: none), Tables 2 and 3 come twice: every
// backend on the sample, with ratios to the fastest direct backend on it, then the whole runs.
std::string paper_tables_section(const CsvTable& runs, const CsvTable& samples, const std::string& out_dir);

// The markdown table of every backend on the recorded sample of `scene` (samples.csv rows),
// with ratios to the fastest direct backend; table 2 or 3 adds the paper's rows of that
// table, 0 none. Empty when the sample holds no row of the scene.
std::string sample_table(const CsvTable& samples, int table, const std::string& scene);

// The paper's time per solve and memory against its Newton system's size, for the growth
// plots of `scene` (block-strips: Table 2, block-strips-mr: Table 3; none for another).
std::vector<ReferencePoint> paper_points(const std::string& scene);

}  // namespace stiction::harness
