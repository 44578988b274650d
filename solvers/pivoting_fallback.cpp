#include "pivoting_fallback.hpp"

#include <cstring>

#include "common/error.hpp"
#include "common/petsc.hpp"

namespace stiction::solvers {

bool factored_by_mumps(KSP ksp) {
  PC pc;
  STICTION_PETSC(KSPGetPC(ksp, &pc));
  PetscBool factor;
  STICTION_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factor, PCLU, PCCHOLESKY, ""));
  if (!factor) return false;
  MatSolverType type = nullptr;
  STICTION_PETSC(PCFactorGetMatSolverType(pc, &type));
  return type && std::strcmp(type, MATSOLVERMUMPS) == 0;
}

bool set_up_with_pivoting_fallback(KSP ksp) {
  STICTION_PETSC(KSPSetUp(ksp));
  PC pc;
  STICTION_PETSC(KSPGetPC(ksp, &pc));
  PCFailedReason reason;
  STICTION_PETSC(PCGetFailedReason(pc, &reason));
  PetscBool factor;
  STICTION_PETSC(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factor, PCLU, PCCHOLESKY, ""));
  if (reason == PC_NOERROR || !factor || factored_by_mumps(ksp)) return false;
  // The solver package cannot change while the PC holds a factor: reset it (which also
  // drops its operators), choose MUMPS and factor again.
  Mat A, P;
  STICTION_PETSC(KSPGetOperators(ksp, &A, &P));
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(A)));
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(P)));
  STICTION_PETSC(PCReset(pc));
  STICTION_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  STICTION_PETSC(KSPSetOperators(ksp, A, P));
  STICTION_PETSC(MatDestroy(&A));
  STICTION_PETSC(MatDestroy(&P));
  STICTION_PETSC(KSPSetUp(ksp));
  return true;
}

}  // namespace stiction::solvers
