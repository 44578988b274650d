#pragma once
// Record and replay of Newton systems, so backends can be compared on exactly the same
// matrices. One folder per system (system-<step>-<iteration>/):
//   system.petsc   PETSc binary: matrix, right side, recorded solution, one IS per field,
//                  the near-null-space vectors, then the pressure mass (mixed systems) and
//                  the multiplier surface's matrices (contact systems), in that order
//   metadata.json  scene, level, solver, step, iteration, unknowns, block size, field
//                  names and sizes, number of near-null vectors, whether a pressure mass
//                  follows and the mixed law's moduli, the multiplier surface's matrices
//                  present, the recording solve's statistics (with its Krylov tolerance when
//                  it was a Krylov solve), PETSc version, git revision
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "nonlinear/linear_solver.hpp"
#include "nonlinear/newton_system.hpp"
#include "run_info.hpp"

namespace stiction::harness {

struct RecordContext {
  std::string scene;
  int level = 0;
  std::string solver;
  RunInfo info;
};

void record_system(const std::string& dir, const nonlinear::NewtonSystem& system, Vec solution,
                   const nonlinear::LinearSolveStats& stats, int step, int iteration, const RecordContext& context);

struct RecordedSystem {
  std::string path;        // the system's folder
  std::string description; // scene, level, step, iteration
  nonlinear::NewtonSystem system;
  PetscVec solution;       // recorded solution
  double krylov_rtol = 0;  // relative tolerance of the recording Krylov solve (0: a direct solve, or not recorded)
  int krylov_restart = 0;  // GMRES restart of the recording solve (0: not GMRES, or not recorded)
};

// "STEP:ITERATION" items (load step, Newton iteration from 1) as pairs; throws on any other form.
std::set<std::pair<int, int>> parse_system_selection(const std::vector<std::string>& items);

// The systems under `dir`, in (step, iteration) order; throws on a missing or unreadable record.
std::vector<std::string> recorded_system_dirs(const std::string& dir);
RecordedSystem load_system(const std::string& system_dir, MPI_Comm comm);

}  // namespace stiction::harness
