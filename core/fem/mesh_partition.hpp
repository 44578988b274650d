#pragma once
// Which MPI rank owns each cell. On this path the mesh itself stays whole on every rank
// (scene::divide_scene gives each rank its part instead); what is divided is the Newton
// system's rows and the state: each rank owns the dofs of the nodes its cells reach first
// (fem::DofLayout), holds those and the ghosts it reads (fem::GhostedVector), and assembles
// its rows of the residual and the tangent from the cells that reach them.
//
// The cells are split by PETSc's MatPartitioning over the dual graph (cells sharing a
// facet), with PT-Scotch, the graph partitioner Debian's PETSc carries (it has no ParMETIS,
// which MatMeshToCellGraph would need to build the dual graph: it is built here), on one
// thread so that the split is the same on every run. One rank owns every cell and calls
// no partitioner.
#include <string>
#include <vector>

#include <mpi.h>

#include "mesh/mesh.hpp"

namespace stiction::fem {

struct MeshPartition {
  int rank = 0, size = 1;
  std::vector<int> cell_owner;   // rank of every cell (the same on every rank)
  std::vector<int> owned_cells;  // this rank's cells, ascending
  // PETSc's MatPartitioningType that split the cells; empty on one rank, and over a mesh part
  // (scene::ScenePart::partitioner names the one that split the whole mesh).
  std::string partitioner;
  bool whole() const { return size == 1; }
};

MeshPartition partition_cells(MPI_Comm comm, const mesh::Mesh& mesh);

// The sum over ranks of each rank's v, on every rank (reduced on rank 0 and broadcast, so
// every rank holds the same bits: every rank must take the Newton driver's decisions alike).
void sum_over_ranks(MPI_Comm comm, std::vector<double>& v);
double sum_over_ranks(MPI_Comm comm, double v);
// The smallest of each rank's cell index c >= 0, or -1 when no rank has one.
int first_cell_over_ranks(MPI_Comm comm, int c);

}  // namespace stiction::fem
