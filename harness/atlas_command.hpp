#pragma once
// `stiction atlas`: where each backend breaks. From a base scene, one scene key at a time
// (an axis: contact[0].friction=0,0.3,1,2; material[0].E=...; load.steps=...; or the mesh
// level) is swept for every backend, each cell a child `stiction solve --set KEY=VALUE` with
// a time and memory limit. A cell's row in atlas.csv: converged or the named reason, Newton
// and Krylov iterations, contact state changes, wall time, peak memory, whether any output
// holds a NaN, and the violation of what must hold in every cell (a crash, a hang, a NaN,
// a failure without a named reason). A pair of keys (--pair) is swept together, every value
// of one with every value of the other, to map where two hard settings meet. report.md (a
// table and a heat map per axis, per pair and backend) is rebuilt after every cell and by
// `stiction report DIR`.
#include <string>
#include <vector>

#include "run_info.hpp"

namespace stiction::harness {

struct AtlasOptions {
  std::string scene;
  int level = 0;
  std::vector<std::string> solvers{"schur-amg", "lu-mumps"};
  std::vector<std::string> axes;  // "KEY=v1,v2,..." (KEY a scene key path, or "level")
  std::vector<std::string> pairs;  // two axes per pair, one after the other
  std::vector<std::string> base;  // KEY=VALUE settings of the base scene, in every cell
  std::string out_dir = "reports/atlas";
  bool resume = false;
  bool quick = false;  // every cell runs the scene's short version (its load.quick_until)
  double time_limit_seconds = 600;
  double memory_limit_mb = 0;  // 0: 90% of the machine's memory
};

void run_atlas(const AtlasOptions& options, const RunInfo& info);

}  // namespace stiction::harness
