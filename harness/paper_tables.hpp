#pragma once
// The paper's Tables 1-3 (reference/lacasse-fortin-block-strips/, compiled in) beside a
// sweep's runs of the block with strips: Table 1 (mesh counts) from any run of
// `block-strips`, Table 2 from `block-strips` (linear), Table 3 from `block-strips-mr`
// (Mooney-Rivlin), with each backend's ratios to lu-mumps next to the paper's GlobalLU /
// Schur ratios, and the converged forces of every backend against lu-mumps' (the same
// Newton tolerance must give the same answer).
#include <string>

#include "csv_table.hpp"

namespace stiction::harness {

// The markdown section, empty when the sweep holds no run of either scene. out_dir holds
// the sweep (runs/<run>/steps.csv gives the forces).
std::string paper_tables_section(const CsvTable& runs, const std::string& out_dir);

}  // namespace stiction::harness
