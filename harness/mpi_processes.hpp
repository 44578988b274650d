#pragma once
// stiction under mpirun. `stiction solve` runs on several processes (the Newton system is
// distributed, the Newton state replicated: nonlinear::QuasiStaticSolver); every other
// command is refused with one message before any work starts. Failures:
//
// * One met alike by every process (Reach::EveryProcess: an input error, since every
//   process reads the same input before any collective operation, or a failure of the
//   Newton state they share): rank 0 prints it, every process exits with its code, and
//   mpirun returns non-zero.
// * Any other failure may be met by one process while the others wait in a collective
//   operation: that process prints it (naming its rank) and aborts the job, so no process
//   is left hanging.
//
// The sweeps (bench, report) start no MPI; under mpirun they see the launcher's variables.
#include <string>

#include "common/error.hpp"

namespace stiction::harness {

struct MpiProcesses {
  int rank = 0, size = 1;
};

// From the launcher's environment (Open MPI, MPICH/PMI), without initialising MPI.
MpiProcesses launched_processes();
// From PETSC_COMM_WORLD (PETSc initialised).
MpiProcesses petsc_processes();

// Throws the refusal (ErrorKind::Input) of a command that runs on one process when launched
// on more than one.
void require_one_process(const MpiProcesses& p, const std::string& command);

// Prints `stiction: <label>: <message>` by the rules above and returns the exit code; does
// not return when it aborts the job.
int report_failure(const MpiProcesses& p, ErrorKind kind, Reach reach, const std::string& message,
                   bool mpi_initialised, const char* label = "error");

}  // namespace stiction::harness
