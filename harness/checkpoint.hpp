#pragma once
// Checkpoint of a solve: after every completed load step `stiction solve` writes the
// converged state (displacement, multipliers, contact states, the step and its pseudo-time)
// and the run's tally of linear solves to <out>/checkpoint.bin, replacing the previous one atomically, so that
// `stiction solve <scene> --restart <out>` continues a failed or killed run from there.
// The file names its scene and level; a restart refuses a checkpoint of another scene,
// level or size.
#include <string>

#include "nonlinear/newton.hpp"

namespace stiction::harness {

struct Checkpoint {
  std::string scene;
  int level = 0;
  nonlinear::QuasiStaticSolver::State state;
  nonlinear::QuasiStaticSolver::LinearTally tally;  // zero from a checkpoint of format 1
  nonlinear::QuasiStaticSolver::CutBack cut_back;    // none from a checkpoint of format 1 or 2
};

void write_checkpoint(const std::string& path, const Checkpoint& c);
// Throws stiction::Error (bad input) when the file is missing, truncated or not a checkpoint.
Checkpoint read_checkpoint(const std::string& path);

}  // namespace stiction::harness
