#pragma once
// report.md of a trade-off sweep, rebuilt from its tradeoff.csv: every run, the Pareto front
// (wall time against the displacement error in H1, the runs no other run beats on both), a
// plot of it (SVG by gnuplot, its script beside it), and for a few error targets the
// fastest setting that meets each, as a command line, with its speed-up over its backend's
// defaults.
#include <string>

namespace stiction::harness {

extern const char* const kTradeoffColumns;

void write_tradeoff_report(const std::string& out_dir);

}  // namespace stiction::harness
