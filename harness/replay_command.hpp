#pragma once
// `stiction replay DIR --solver NAME`: solve recorded Newton systems with any backend and
// report the same statistics as a live run, plus the difference to the recorded solution.
#include <string>

#include "run_info.hpp"

namespace stiction::harness {

struct ReplayOptions {
  std::string record_dir;
  std::string solver = "lu-mumps";
  std::string csv_path;  // optional CSV of the table
};

// Returns the largest relative difference to the recorded solutions.
double run_replay(const ReplayOptions& options, const RunInfo& info);

}  // namespace stiction::harness
