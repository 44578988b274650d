#pragma once
// The CSV of a sweep (bench's runs.csv, tradeoff.csv, atlas.csv): started with its
// provenance header and columns, or continued (--resume) when it has no column this
// version does not write.
#include <functional>
#include <map>
#include <string>

#include "csv_table.hpp"
#include "run_info.hpp"

namespace stiction::harness {

// A new file gets header() (comment lines, each ending in a newline) and the columns; an
// existing one is refused without resume or when it has a column this version does not
// write; one that lacks some of this version's columns (an older version's sweep) is
// rewritten with them, empty in its rows; then its rows are returned and a "# resumed" line
// is appended. A resumed table whose sweep was started by a binary of another revision is
// refused unless allow_other_revision (the rows then name their revisions).
CsvTable open_sweep_table(const std::string& path, const std::string& columns, bool resume, const RunInfo& info,
                          const std::function<std::string()>& header, bool allow_other_revision = false);

// The revision of the binary that started a sweep: its table's "git revision" header line
// ("" when it has none).
std::string sweep_revision(const CsvTable& table);

// The upgrade step of open_sweep_table alone, for an existing file a resumed sweep appends
// to beside its main table (bench's steps.csv): rewritten with the missing columns, or
// refused when it has one this version does not write; returns its rows.
CsvTable upgrade_sweep_columns(const std::string& path, const std::string& columns);

// A bench run's status as the report tables show it: "ok", followed by the PETSc options the
// sweep gave its backend beyond its defaults (the petsc_options column) when there are any;
// otherwise the status and what stopped the run.
std::string run_status_text(const std::map<std::string, std::string>& row);
// Those PETSc options beyond the backend's defaults ("" when none, or for a sweep older
// than the column).
std::string extra_petsc_options(const std::map<std::string, std::string>& row);

// A run its time limit stopped after it had finished some linear solves: its per-solve
// figures (seconds and Krylov iterations per solve, over those solves) are measured, its
// totals are not, and its peak memory is a lower bound of the whole run's.
bool stopped_with_solves(const std::map<std::string, std::string>& row);
// A run's peak memory in MB as the report tables show it: the figure of a finished run, a
// lower bound ("≥") for one stopped_with_solves, "—" otherwise.
std::string peak_memory_text(const std::map<std::string, std::string>& row);

}  // namespace stiction::harness
