#pragma once
// report.md of a sweep, rebuilt from its runs.csv (post-processing kept separate from
// running, so a report can be remade without rerunning anything).
#include <string>

namespace stiction::harness {

void write_bench_report(const std::string& out_dir);

}  // namespace stiction::harness
