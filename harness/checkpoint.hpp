#pragma once
// Checkpoint of a solve: after every completed load step `stiction solve` writes the
// converged state (displacement, multipliers, contact states, the step and its pseudo-time)
// and the run's tally of linear solves to <out>/checkpoint.bin, replacing the previous one atomically, so that
// `stiction solve <scene> --restart <out>` continues a failed or killed run from there.
// The file names its scene and level; a restart refuses a checkpoint of another scene,
// level or size.
#include <string>

#include <mpi.h>

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
// The same on several MPI processes (collective): rank 0 reads the file, which the others
// need not see (rank 0 alone writes it, perhaps on a disk of its own node), and sends them
// everything but the state's u, which it keeps alone (QuasiStaticSolver::restore scatters
// it); a failure is thrown on every process with rank 0's message.
Checkpoint read_checkpoint(MPI_Comm comm, const std::string& path);

}  // namespace stiction::harness
