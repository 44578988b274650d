#pragma once
// The global stiffness matrix of a displacement space: AIJ with block size dim and the
// exact nonzero pattern of the node graph (two nodes couple when they share a cell).
//
// Why not plain MatSetValues: for P2 tetrahedra an element matrix has 900 entries and
// PETSc searches every column of every row. Here all dim x dim entries of a node pair
// share one position, so add() does one search per node pair and writes straight into the
// sequential AIJ value array. The pattern is preallocated node by node, so no second
// full-size copy of the column indices ever exists (peak memory stays near the matrix).
// Any other matrix type (e.g. MPI AIJ) falls back to MatSetValues.
#include <vector>

#include "common/petsc.hpp"
#include "fem/displacement_space.hpp"

namespace stiction::fem {

class StiffnessMatrix {
public:
  StiffnessMatrix(MPI_Comm comm, const DisplacementSpace& space);

  Mat mat() const { return A_; }
  bool direct_insertion() const { return direct_; }

  // Zero the values; element matrices are added between begin and end.
  void begin_assembly();
  // Ke: row-major (n_nodes * dim)^2, dof order (node, component).
  void add(const int* nodes, int n_nodes, const double* Ke);
  void end_assembly();

private:
  int degree(int node) const { return offsets_[node + 1] - offsets_[node]; }
  bool layout_matches_petsc() const;

  int dim_;
  std::vector<int> offsets_, neighbours_;  // node graph, CSR, neighbours sorted
  PetscMat A_;
  bool direct_ = false;
  PetscScalar* values_ = nullptr;  // valid between begin_assembly and end_assembly
};

}  // namespace stiction::fem
