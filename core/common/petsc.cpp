#include "common/petsc.hpp"

#include <fmt/format.h>

#include "common/process_memory.hpp"

namespace stiction {

void petsc_check(PetscErrorCode ierr, const char* expr, const char* file, int line) {
  if (ierr == 0) return;
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(ierr, &text, &specific);
  throw Error(fmt::format("PETSc error {} in {} ({}:{}): {}{}{}", static_cast<int>(ierr), expr, file,
                          line, text ? text : "", specific && *specific ? ": " : "",
                          specific ? specific : ""),
              ErrorKind::Numerical);
}

PetscSession::PetscSession(int* argc, char*** argv) {
  PetscBool initialised = PETSC_FALSE;
  PetscInitialized(&initialised);
  if (initialised) return;
  // CombBLAS's settings were made when the program was loaded; nothing MPI_Init loads
  // calls mallopt.
  return_freed_memory_to_the_system();
  STICTION_PETSC(PetscInitialize(argc, argv, nullptr, nullptr));
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  // Default signal behaviour: a closed pipe (stiction replay ... | head) ends the process
  // quietly instead of a PETSc crash report and MPI_Abort.
  PetscPopSignalHandler();
}

PetscSession::~PetscSession() {
  PetscBool finalised = PETSC_FALSE;
  PetscFinalized(&finalised);
  if (!finalised) PetscFinalize();
}

std::string petsc_version_string() {
  char buf[256];
  PetscGetVersion(buf, sizeof buf);
  return buf;
}

PatternKey pattern_key(Mat A) {
  PatternKey k;
  STICTION_PETSC(PetscObjectGetId(reinterpret_cast<PetscObject>(A), &k.id));
  STICTION_PETSC(MatGetNonzeroState(A, &k.state));
  return k;
}

}  // namespace stiction
