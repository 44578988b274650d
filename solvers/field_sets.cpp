#include "field_sets.hpp"

#include <vector>

#include "common/error.hpp"

namespace stiction::solvers {

PetscIS union_of_fields(const nonlinear::NewtonSystem& system, std::initializer_list<const char*> names) {
  std::vector<IS> parts;
  int block_size = 0;
  for (const char* name : names)
    if (const auto* f = system.field(name)) {
      parts.push_back(f->is);
      if (block_size == 0) block_size = f->block_size;
    }
  if (parts.empty()) throw Error("union_of_fields: the system has none of the named fields", ErrorKind::Internal);
  PetscIS out;
  STICTION_PETSC(ISConcatenate(system.comm, static_cast<PetscInt>(parts.size()), parts.data(), out.out()));
  STICTION_PETSC(ISSort(out));
  STICTION_PETSC(ISSetBlockSize(out, block_size));
  return out;
}

PetscIS complement_in(Mat A, IS is) {
  PetscInt first, last;
  STICTION_PETSC(MatGetOwnershipRange(A, &first, &last));
  PetscIS out;
  STICTION_PETSC(ISComplement(is, first, last, out.out()));
  return out;
}

PetscNullSpace restrict_null_space(MatNullSpace space, IS is) {
  PetscBool has_constant;
  PetscInt n;
  const Vec* vecs;
  STICTION_PETSC(MatNullSpaceGetVecs(space, &has_constant, &n, &vecs));
  std::vector<Vec> restricted(static_cast<size_t>(n));
  for (PetscInt k = 0; k < n; ++k) {
    Vec part;
    STICTION_PETSC(VecGetSubVector(vecs[k], is, &part));
    STICTION_PETSC(VecDuplicate(part, &restricted[k]));
    STICTION_PETSC(VecCopy(part, restricted[k]));
    STICTION_PETSC(VecRestoreSubVector(vecs[k], is, &part));
  }
  PetscNullSpace out;
  STICTION_PETSC(MatNullSpaceCreate(PetscObjectComm(reinterpret_cast<PetscObject>(space)), has_constant, n,
                                    restricted.data(), out.out()));
  for (Vec& v : restricted) STICTION_PETSC(VecDestroy(&v));
  return out;
}

}  // namespace stiction::solvers
