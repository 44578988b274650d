#include "mpi_processes.hpp"

#include <fmt/format.h>
#include <petscsys.h>

#include <cstdio>
#include <cstdlib>

namespace stiction::harness {

namespace {

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  if (!v || !*v) return fallback;
  char* end = nullptr;
  const long n = std::strtol(v, &end, 10);
  return end && *end == '\0' && n >= 0 ? static_cast<int>(n) : fallback;
}

}  // namespace

MpiProcesses launched_processes() {
  MpiProcesses p;
  p.size = env_int("OMPI_COMM_WORLD_SIZE", env_int("PMI_SIZE", 1));
  p.rank = env_int("OMPI_COMM_WORLD_RANK", env_int("PMI_RANK", 0));
  return p;
}

MpiProcesses petsc_processes() {
  MpiProcesses p;
  MPI_Comm_size(PETSC_COMM_WORLD, &p.size);
  MPI_Comm_rank(PETSC_COMM_WORLD, &p.rank);
  return p;
}

void require_one_process(const MpiProcesses& p, const std::string& command) {
  if (p.size <= 1) return;
  throw Error(fmt::format("`stiction {}` runs on one MPI process (launched on {}); `stiction solve` is the "
                          "command that runs on several", command, p.size));
}

int report_failure(const MpiProcesses& p, ErrorKind kind, Reach reach, const std::string& message,
                   bool mpi_initialised, const char* label) {
  if (p.size <= 1 || reach == Reach::EveryProcess) {
    if (p.rank == 0) fmt::print(stderr, "stiction: {}: {}\n", label, message);
    return static_cast<int>(kind);
  }
  fmt::print(stderr, "stiction: {}: (process {} of {}) {}\n", label, p.rank, p.size, message);
  std::fflush(stderr);
  if (mpi_initialised) MPI_Abort(PETSC_COMM_WORLD, static_cast<int>(kind));
  return static_cast<int>(kind);
}

}  // namespace stiction::harness
