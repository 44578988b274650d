#pragma once
// Index sets made from the Newton system's named fields. On several processes a field's
// unknowns are not one contiguous range of the global numbering (each process numbers its
// own unknowns of every field in turn), so the preconditioners build the sets they need
// from the fields rather than from ranges.
#include <initializer_list>

#include "common/petsc.hpp"
#include "nonlinear/newton_system.hpp"

namespace stiction::solvers {

// The union of the named fields (each process's owned part, ascending); absent fields are
// skipped. Block size: the first named field's.
PetscIS union_of_fields(const nonlinear::NewtonSystem& system, std::initializer_list<const char*> names);

// The unknowns A's rows own on this process that `is` does not hold (ascending).
PetscIS complement_in(Mat A, IS is);

// The vectors of a near-null space of the whole system restricted to the unknowns of `is`
// (zero outside the displacement, so they stay orthonormal).
PetscNullSpace restrict_null_space(MatNullSpace space, IS is);

}  // namespace stiction::solvers
