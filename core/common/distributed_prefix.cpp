#include "common/distributed_prefix.hpp"

#include "common/petsc.hpp"

namespace stiction {

namespace {

using PetscScatter = PetscOwner<VecScatter, VecScatterDestroy>;

// Replaces v's entries by their exclusive prefix sum in global order; returns the sum of all.
long long scan_in_place(MPI_Comm comm, Vec v) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  PetscInt n_range = 0;
  STICTION_PETSC(VecGetLocalSize(v, &n_range));
  PetscScalar* a = nullptr;
  STICTION_PETSC(VecGetArray(v, &a));
  long long range_total = 0, before = 0, total = 0;
  for (PetscInt i = 0; i < n_range; ++i) {
    const long long count = static_cast<long long>(PetscRealPart(a[i]));
    a[i] = static_cast<PetscScalar>(range_total);
    range_total += count;
  }
  MPI_Exscan(&range_total, &before, 1, MPI_LONG_LONG, MPI_SUM, comm);
  if (rank == 0) before = 0;  // MPI_Exscan leaves rank 0's result undefined
  for (PetscInt i = 0; i < n_range; ++i) a[i] += static_cast<PetscScalar>(before);
  STICTION_PETSC(VecRestoreArray(v, &a));
  MPI_Allreduce(&range_total, &total, 1, MPI_LONG_LONG, MPI_SUM, comm);
  return total;
}

// v's entries at the wanted global indices, whichever process owns them.
std::vector<long long> read_at(Vec v, const std::vector<PetscInt>& wanted) {
  PetscIS from;
  STICTION_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(wanted.size()), wanted.data(), PETSC_USE_POINTER, from.out()));
  PetscVec read;
  STICTION_PETSC(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(wanted.size()), read.out()));
  PetscScatter scatter;
  STICTION_PETSC(VecScatterCreate(v, from, read, nullptr, scatter.out()));
  STICTION_PETSC(VecScatterBegin(scatter, v, read, INSERT_VALUES, SCATTER_FORWARD));
  STICTION_PETSC(VecScatterEnd(scatter, v, read, INSERT_VALUES, SCATTER_FORWARD));
  std::vector<long long> values(wanted.size());
  const PetscScalar* r = nullptr;
  STICTION_PETSC(VecGetArrayRead(read, &r));
  for (size_t k = 0; k < wanted.size(); ++k) values[k] = static_cast<long long>(PetscRealPart(r[k]));
  STICTION_PETSC(VecRestoreArrayRead(read, &r));
  return values;
}

}  // namespace

std::vector<long long> exclusive_prefix(MPI_Comm comm, PetscInt n, const std::vector<PetscInt>& at,
                                        const std::vector<PetscScalar>& counts, const std::vector<PetscInt>& wanted,
                                        long long* total) {
  PetscVec v;
  STICTION_PETSC(VecCreateMPI(comm, PETSC_DECIDE, n, v.out()));
  STICTION_PETSC(VecSet(v, 0.0));
  STICTION_PETSC(VecSetValues(v, static_cast<PetscInt>(at.size()), at.data(), counts.data(), INSERT_VALUES));
  STICTION_PETSC(VecAssemblyBegin(v));
  STICTION_PETSC(VecAssemblyEnd(v));
  *total = scan_in_place(comm, v);
  return read_at(v, wanted);
}

}  // namespace stiction
