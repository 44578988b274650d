#pragma once
// The CSV of a sweep (bench's runs.csv, tradeoff.csv, atlas.csv): started with its
// provenance header and columns, or continued (--resume) only when it has the same columns.
#include <functional>
#include <string>

#include "csv_table.hpp"
#include "run_info.hpp"

namespace stiction::harness {

// A new file gets header() (comment lines, each ending in a newline) and the columns; an
// existing one is refused without resume or with other columns (an older version's sweep),
// else its rows are returned and a "# resumed" line is appended.
CsvTable open_sweep_table(const std::string& path, const std::string& columns, bool resume, const RunInfo& info,
                          const std::function<std::string()>& header);

}  // namespace stiction::harness
