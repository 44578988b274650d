#pragma once
// Exact block inverses for preconditioner verification on small systems.
#include <petscksp.h>

#include <string>

#include <memory>

#include "hierarchical_pc.hpp"
#include "nonlinear/newton.hpp"
#include "nonlinear/newton_system.hpp"
#include "scene/scene.hpp"

namespace stiction::test {

// The last Newton system of load step 1 of a built-in scene at level 0, assembled by the
// real driver (solved with lu-mumps).
struct StepSystem {
  explicit StepSystem(const std::string& builtin_scene);
  std::unique_ptr<scene::Scene> scene;
  std::unique_ptr<nonlinear::LinearSolver> lu;
  std::unique_ptr<nonlinear::QuasiStaticSolver> newton;
  const nonlinear::NewtonSystem& system() const { return newton->system(); }
};

// Dense S = D - C A^-1 B (A sparse, factorised by PETSc's LU).
Mat dense_schur_complement(Mat A, Mat B, Mat C, Mat D);

// GMRES (right preconditioned, rtol 1e-10) on the system with p as shell preconditioner;
// returns the iterations and the true relative residual.
int gmres_iterations(const nonlinear::NewtonSystem& sys, const solvers::ShellPreconditioner& p, double* residual);

// HP on sys with exact sub-solves: LU of A_ll and the exact dense S_q, full form (so it is
// the exact inverse of the displacement block). Options go under `prefix`. Owns S_q.
struct ExactHierarchical {
  ExactHierarchical(const nonlinear::NewtonSystem& sys, const std::string& prefix);
  ~ExactHierarchical();
  solvers::HierarchicalPreconditioner hp;
  Mat schur = nullptr;
};

// Sets "-<prefix><key> value" for each pair (nullptr value for flags).
void set_options(const std::string& prefix, std::initializer_list<std::pair<const char*, const char*>> options);

}  // namespace stiction::test
