#include "fem/mesh_partition.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <scotch.h>  // after <cstdint> and <cstdio>, which it needs

#include "common/petsc.hpp"

namespace stiction::fem {

namespace {

// Neighbours across facets of cells [first, last), as compressed rows (MatCreateMPIAdj's
// input, which it takes over: allocated with PetscMalloc).
void dual_graph_rows(const mesh::Mesh& mesh, int first, int last, PetscInt** ia, PetscInt** ja) {
  const int nv = mesh.vertices_per_cell(), nc = mesh.n_cells();
  // Every facet of every cell as (sorted vertices, cell); equal keys are neighbours.
  std::vector<std::pair<std::array<int, 3>, int>> facets;
  facets.reserve(static_cast<size_t>(nc) * nv);
  for (int c = 0; c < nc; ++c)
    for (const auto& key : mesh::cell_facet_keys(mesh.cell(c), mesh.dim)) facets.push_back({key, c});
  std::sort(facets.begin(), facets.end());
  std::vector<std::vector<PetscInt>> adjacent(static_cast<size_t>(last - first));
  for (size_t i = 0; i + 1 < facets.size(); ++i)
    if (facets[i].first == facets[i + 1].first) {
      const int a = facets[i].second, b = facets[i + 1].second;
      if (a >= first && a < last) adjacent[a - first].push_back(b);
      if (b >= first && b < last) adjacent[b - first].push_back(a);
    }
  size_t n_entries = 0;
  for (auto& row : adjacent) std::sort(row.begin(), row.end()), n_entries += row.size();
  STICTION_PETSC(PetscMalloc1(adjacent.size() + 1, ia));
  STICTION_PETSC(PetscMalloc1(std::max<size_t>(n_entries, 1), ja));
  (*ia)[0] = 0;
  for (size_t r = 0; r < adjacent.size(); ++r) {
    std::copy(adjacent[r].begin(), adjacent[r].end(), *ja + (*ia)[r]);
    (*ia)[r + 1] = (*ia)[r] + static_cast<PetscInt>(adjacent[r].size());
  }
}

}  // namespace

MeshPartition partition_cells(MPI_Comm comm, const mesh::Mesh& mesh) {
  MeshPartition p;
  MPI_Comm_rank(comm, &p.rank);
  MPI_Comm_size(comm, &p.size);
  const int nc = mesh.n_cells();
  if (p.size == 1) {
    p.cell_owner.assign(nc, 0);
    p.owned_cells.resize(nc);
    for (int c = 0; c < nc; ++c) p.owned_cells[c] = c;
    return p;
  }
  // The partitioner reads the graph distributed in contiguous blocks of cells.
  const int first = static_cast<int>(static_cast<long long>(nc) * p.rank / p.size);
  const int last = static_cast<int>(static_cast<long long>(nc) * (p.rank + 1) / p.size);
  PetscInt *ia = nullptr, *ja = nullptr;
  dual_graph_rows(mesh, first, last, &ia, &ja);
  PetscMat adjacency;
  STICTION_PETSC(MatCreateMPIAdj(comm, last - first, nc, ia, ja, nullptr, adjacency.out()));
  MatPartitioning part;
  STICTION_PETSC(MatPartitioningCreate(comm, &part));
  STICTION_PETSC(MatPartitioningSetAdjacency(part, adjacency));
  STICTION_PETSC(MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH));
  STICTION_PETSC(MatPartitioningSetFromOptions(part));  // -mat_partitioning_type overrides
  PetscIS destination, everywhere;
  // Scotch 7 runs its partitioning on as many threads as cores unless told otherwise, and
  // the threads' race made the partition, and with it every Krylov count of a distributed
  // run, change from run to run; on one thread it is the same every time (a setting in the
  // environment wins).
  setenv("SCOTCH_PTHREAD_NUMBER", "1", 0);
  // Scotch's random state lives as long as the process and each partition draws from it:
  // reset, the partition of a graph is the same at every call of one process (tests build
  // several solvers) and the same as in a fresh process.
  SCOTCH_randomReset();
  const PetscErrorCode ierr = MatPartitioningApply(part, destination.out());
  MatPartitioningType type = nullptr;
  if (!ierr) MatPartitioningGetType(part, &type);
  p.partitioner = type ? type : "";
  MatPartitioningDestroy(&part);
  STICTION_PETSC(ierr);
  STICTION_PETSC(ISAllGather(destination, everywhere.out()));
  const PetscInt* owner;
  STICTION_PETSC(ISGetIndices(everywhere, &owner));
  p.cell_owner.assign(owner, owner + nc);
  STICTION_PETSC(ISRestoreIndices(everywhere, &owner));
  for (int c = 0; c < nc; ++c)
    if (p.cell_owner[c] == p.rank) p.owned_cells.push_back(c);
  return p;
}

void sum_over_ranks(MPI_Comm comm, std::vector<double>& v) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  const int n = static_cast<int>(v.size());
  if (rank == 0)
    MPI_Reduce(MPI_IN_PLACE, v.data(), n, MPI_DOUBLE, MPI_SUM, 0, comm);
  else
    MPI_Reduce(v.data(), nullptr, n, MPI_DOUBLE, MPI_SUM, 0, comm);
  MPI_Bcast(v.data(), n, MPI_DOUBLE, 0, comm);
}

double sum_over_ranks(MPI_Comm comm, double v) {
  std::vector<double> one{v};
  sum_over_ranks(comm, one);
  return one[0];
}

int first_cell_over_ranks(MPI_Comm comm, int c) {
  int mine = c >= 0 ? c : std::numeric_limits<int>::max(), first;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  return first == std::numeric_limits<int>::max() ? -1 : first;
}

}  // namespace stiction::fem
