#include "registry.hpp"

#include <fmt/format.h>

#include "common/error.hpp"
#include "common/petsc.hpp"

namespace stiction::solvers {

#define STICTION_BACKEND(id, name, description, package, processes) \
  std::unique_ptr<nonlinear::LinearSolver> make_##id(MPI_Comm comm);
#include "backend_list.hpp"
#undef STICTION_BACKEND

namespace {

constexpr int kOneProcess = 1, kAnyProcesses = 0;

// Empty when PETSc was built with the external package (or none is needed), else the reason.
std::function<std::string()> needs_package(const char* package) {
  return [package]() -> std::string {
    if (!*package) return "";
    PetscBool has = PETSC_FALSE;
    PetscHasExternalPackage(package, &has);
    return has ? "" : fmt::format("PETSc was built without {}", package);
  };
}

}  // namespace

const std::vector<BackendInfo>& backends() {
  static const std::vector<BackendInfo> all{
#define STICTION_BACKEND(id, name, description, package, processes) \
  {name, description, needs_package(package), make_##id, processes == kAnyProcesses},
#include "backend_list.hpp"
#undef STICTION_BACKEND
  };
  return all;
}

std::string backend_names() {
  std::string s;
  for (const auto& b : backends()) s += (s.empty() ? "" : ", ") + b.name;
  return s;
}

std::unique_ptr<nonlinear::LinearSolver> create_solver(const std::string& name, MPI_Comm comm) {
  for (const auto& b : backends()) {
    if (b.name != name) continue;
    const std::string why = b.unavailable_reason();
    if (!why.empty()) throw Error(fmt::format("solver backend '{}' is not available: {}", name, why));
    int processes = 1;
    MPI_Comm_size(comm, &processes);
    if (processes > 1 && !b.distributed) {
      std::string usable;
      for (const auto& other : backends())
        if (other.distributed) usable += (usable.empty() ? "" : ", ") + other.name;
      throw Error(fmt::format("solver backend '{}' runs on one MPI process (launched on {}); on several use one "
                              "of: {}", name, processes, usable));
    }
    return b.create(comm);
  }
  throw Error(fmt::format("unknown solver backend '{}' (valid: {})", name, backend_names()));
}

}  // namespace stiction::solvers
