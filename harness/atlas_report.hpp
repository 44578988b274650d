#pragma once
// report.md of a stability atlas, rebuilt from its atlas.csv: the cells that broke what must
// hold, then per axis a table (value x backend) and a heat map (SVG by gnuplot, Newton
// iterations of the converged cells, the failed ones marked); per pair of axes, for each
// backend, a table and a heat map of the first key's values against the second's.
#include <string>

namespace stiction::harness {

extern const char* const kAtlasColumns;
// Between the keys of a pair in atlas.csv's axis column, and between their values.
inline constexpr const char* kPairSeparator = " & ";

// A cell's directory under runs/ and its key in atlas.csv: the key's brackets and any other
// non-word character as '_' (so a value's commas, which atlas.csv holds as ';', match).
std::string cell_id(const std::string& key, const std::string& value, const std::string& solver);

void write_atlas_report(const std::string& out_dir);

}  // namespace stiction::harness
