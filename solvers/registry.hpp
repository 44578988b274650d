#pragma once
// The registry of linear-solver backends, built from the explicit list in backend_list.hpp
// (no static self-registration the linker could drop). Adding a backend is one new file
// plus one line in that list.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "nonlinear/linear_solver.hpp"

namespace stiction::solvers {

struct BackendInfo {
  std::string name;         // also the PETSc options prefix, '-' -> '_'
  std::string description;  // one line
  // Empty when usable in this build, else why not (a missing PETSc package).
  std::function<std::string()> unavailable_reason;
  std::function<std::unique_ptr<nonlinear::LinearSolver>(MPI_Comm)> create;
  bool distributed = false;  // runs on a system distributed over several MPI processes
};

const std::vector<BackendInfo>& backends();
// Throws stiction::Error listing the valid names for an unknown or unavailable backend, or
// for one that runs on one process when comm has several.
std::unique_ptr<nonlinear::LinearSolver> create_solver(const std::string& name, MPI_Comm comm);
// Names of every registered backend, comma separated.
std::string backend_names();

}  // namespace stiction::solvers
