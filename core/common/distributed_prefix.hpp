#pragma once
// The exclusive prefix sum over a global index range [0, n) of counts that the processes
// give at some indices (each index by one process at most; the others count zero), read at
// the wanted indices, in the order of `wanted`; *total gets the sum of all counts. What
// numbers entities consistently across processes (the whole mesh's edges of a mesh part,
// the pressure dofs of a part's vertices): a PETSc vector holds the counts, each process
// scans its range and offsets it by the ranges before (MPI_Exscan), a scatter reads the
// prefixes. Collective over comm.
#include <petscvec.h>

#include <vector>

namespace stiction {

std::vector<long long> exclusive_prefix(MPI_Comm comm, PetscInt n, const std::vector<PetscInt>& at,
                                        const std::vector<PetscScalar>& counts, const std::vector<PetscInt>& wanted,
                                        long long* total);

}  // namespace stiction
