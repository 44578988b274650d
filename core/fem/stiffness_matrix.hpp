#pragma once
// The global Newton matrix of a field space: AIJ with the exact nonzero pattern of the node
// graph (two nodes couple when they share a cell), block size dim when there is no
// pressure field.
//
// Row layout (all rows of one node share it): the dim displacement columns of each
// neighbour node in node order, then, on a mixed body, the pressure column of each
// neighbouring vertex. Vertices are numbered before edge nodes, so a node's vertex
// neighbours are a prefix of its sorted neighbour list and one search per node pair
// locates every entry of that pair.
//
// Why not plain MatSetValues: for P2 tetrahedra an element matrix has 900+ entries and
// PETSc searches every column of every row; here add() writes straight into the
// sequential AIJ value array. The pattern is preallocated node by node, so no second
// full-size copy of the column indices ever exists (peak memory stays near the matrix).
// Any other matrix type (e.g. MPI AIJ) falls back to MatSetValues.
#include <vector>

#include "common/petsc.hpp"
#include "fem/field_space.hpp"

namespace stiction::fem {

class StiffnessMatrix {
public:
  StiffnessMatrix(MPI_Comm comm, const FieldSpace& space);

  Mat mat() const { return A_; }
  bool direct_insertion() const { return direct_; }

  // Zero the values; element matrices are added between begin and end.
  void begin_assembly();
  // Ke: row-major m x m with m = n_nodes * dim + n_pressure_nodes; element dof order:
  // (node, component) for every node, then the pressure of nodes[0 .. n_pressure_nodes).
  void add(const int* nodes, int n_nodes, int n_pressure_nodes, const double* Ke);
  void end_assembly();

private:
  int degree(int node) const { return offsets_[node + 1] - offsets_[node]; }
  bool layout_matches_petsc() const;
  std::vector<PetscInt> row_columns(int node) const;

  const FieldSpace* space_;
  int dim_;
  std::vector<int> offsets_, neighbours_;  // node graph, CSR, neighbours sorted
  std::vector<int> vertex_degree_;         // neighbours that are vertices (a prefix)
  std::vector<char> mixed_;                // node on a body with a pressure field
  std::vector<PetscInt> row_start_;        // direct layout, per global row
  PetscMat A_;
  bool direct_ = false;
  PetscScalar* values_ = nullptr;  // valid between begin_assembly and end_assembly
};

}  // namespace stiction::fem
