#pragma once
// report.md of a stability atlas, rebuilt from its atlas.csv: the cells that broke what must
// hold, then per axis a table (value x backend) and a heat map (SVG by gnuplot, Newton
// iterations of the converged cells, the failed ones marked).
#include <string>

namespace stiction::harness {

extern const char* const kAtlasColumns;

void write_atlas_report(const std::string& out_dir);

}  // namespace stiction::harness
