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
// sequential AIJ value array. The pattern (row starts and columns) is built once, node by
// node, and is the matrix's own storage (seq_aij_over), so no second copy of it exists.
//
// On several MPI ranks (a DofLayout that is not the identity) the matrix is PETSc's MPIAIJ
// in the layout's numbering, and each rank writes only its own rows: it computes the
// element matrices of the cells that reach them (DofLayout::row_cells: its cells and the
// layer around them that holds one of its nodes) and adds each owned row's entries
// straight into the value arrays of the MPIAIJ's two sequential parts (diagonal and
// off-diagonal block), at positions worked out once from the node graph. No entry travels
// between ranks; the price is the element matrices of that one layer of cells, computed on
// both sides of a cut. Its size is the whole system's (the multiplier rows, owned by the
// slave nodes' ranks, stay empty here).
//
// take_arrays() hands the assembled matrix over (a contact system merges its blocks into
// its values, see build_augmented_matrix), so the tangent and the augmented matrix do not
// both exist; the next begin_assembly() writes the pattern again and makes a fresh matrix.
// On several ranks the augmented matrix is built from a copy of the tangent's rows, and
// release() then drops the tangent for the same reason.
#include <memory>
#include <vector>

#include "common/csr_matrix.hpp"
#include "common/petsc.hpp"
#include "fem/dof_layout.hpp"
#include "fem/field_space.hpp"

namespace stiction::fem {

class StiffnessMatrix {
public:
  StiffnessMatrix(MPI_Comm comm, const FieldSpace& space);  // one rank
  StiffnessMatrix(const DofLayout& layout, const FieldSpace& space);

  Mat mat() const { return A_; }  // null after take_arrays() or release() until the next begin_assembly()
  PetscInt block_size() const { return space_->has_pressure() ? 1 : dim_; }

  // Zero the values; element matrices are added between begin and end.
  void begin_assembly();
  // Ke: row-major m x m with m = n_nodes * dim + n_pressure_nodes; element dof order:
  // (node, component) for every node, then the pressure of nodes[0 .. n_pressure_nodes).
  void add(const int* nodes, int n_nodes, int n_pressure_nodes, const double* Ke);
  void end_assembly();
  // The assembled matrix's arrays; this object drops the matrix and forgets the values.
  // One rank only: on several, the augmented matrix is built from mat().
  CsrArrays take_arrays();
  // Drops the assembled matrix (several ranks: once the augmented matrix holds its rows, so
  // that the two do not both exist while the system is solved); the next begin_assembly()
  // makes a fresh one over the same pattern.
  void release();
  bool distributed() const { return layout_ && !layout_->identity(); }

private:
  int degree(int node) const { return offsets_[node + 1] - offsets_[node]; }
  void row_columns(int node, std::vector<PetscInt>& cols) const;
  void build_node_graph();
  void build_row_starts();
  void build_columns();
  void create_matrix();
  void create_distributed_matrix();
  void lay_out_owned_rows(std::vector<PetscInt>& d_nnz, std::vector<PetscInt>& o_nnz);
  int node_rows(int a, PetscInt* rows) const;
  void sorted_columns(int a, std::vector<PetscInt>& sorted, std::vector<int>& place) const;
  void check_distributed_pattern(const std::vector<PetscInt>& d_nnz, const std::vector<PetscInt>& o_nnz);
  void add_distributed(const int* nodes, int n_nodes, int n_pressure_nodes, const double* Ke);

  const FieldSpace* space_;
  const DofLayout* layout_ = nullptr;
  int dim_;
  std::vector<int> offsets_, neighbours_;  // node graph, CSR, neighbours sorted
  std::vector<int> vertex_degree_;         // neighbours that are vertices (a prefix)
  std::vector<char> mixed_;                // node on a body with a pressure field
  MPI_Comm comm_;
  std::shared_ptr<const std::vector<PetscInt>> row_start_, columns_;  // the pattern, per global row
  bool layout_checked_ = false;
  std::shared_ptr<std::vector<PetscScalar>> values_storage_;
  PetscMat A_;
  PetscScalar* values_ = nullptr;  // valid between begin_assembly and end_assembly
  // Several ranks: where neighbour j of owned node a starts in a's rows (indexed like
  // neighbours_), as an offset into the row of the diagonal part (>= 0) or -1 - the offset
  // into the row of the off-diagonal part; the first for its displacement columns, the
  // second for its pressure column (vertex neighbours of mixed nodes). Between begin and
  // end of an assembly, each part's row starts and values.
  std::vector<int> column_slot_, pressure_slot_;
  std::vector<PetscInt> diagonal_length_, off_diagonal_length_;  // per owned row, in each part
  bool rows_laid_out_ = false;
  PetscInt part_entries_[2] = {0, 0};
  Mat parts_[2] = {nullptr, nullptr};
  const PetscInt* part_row_start_[2] = {nullptr, nullptr};
  PetscScalar* part_values_[2] = {nullptr, nullptr};
};

}  // namespace stiction::fem
