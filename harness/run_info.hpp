#pragma once
// How a result was made (style.md habit 1): command line, git revision, PETSc and BLAS,
// threads, machine. Written at the top of every CSV and report.
#include <string>
#include <vector>

namespace stiction::harness {

struct RunInfo {
  std::string command_line;
  std::string git_revision;
  std::string petsc_version;
  std::string blas;          // where libblas.so.3 points
  std::string threads;       // OMP/OPENBLAS thread settings
  std::string machine;       // cores and memory
  std::string allocator;     // how freed memory goes back to the system (peak RSS depends on it)
  std::string date;
};

// The git revision the binary was built from (generated at build time by
// cmake/build_revision.cmake). collect_run_info reports it as the run's revision, adding the
// source tree's revision when that has moved on since the build.
const char* build_revision();

RunInfo collect_run_info(int argc, char** argv);
// "# key: value" lines, for CSV headers (prefix "# ") or markdown (prefix "- ").
std::string format_run_info(const RunInfo& info, const std::string& line_prefix);

}  // namespace stiction::harness
