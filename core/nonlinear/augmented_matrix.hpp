#pragma once
// The augmented Newton matrix of a constrained problem: the assembled tangent A (n x n,
// compressed rows) bordered by sparse constraint blocks, as one AIJ matrix of size n + m
// that every backend (direct, ILU, AMG, Schur) can take. Built by merging compressed rows,
// so its cost is one pass over A's entries; A's value array is reused for the result, so
// the tangent and the augmented matrix never both exist in full.
#include "common/csr_matrix.hpp"
#include "common/petsc.hpp"
#include "fem/dof_layout.hpp"
#include "nonlinear/multiplier_constraint.hpp"

namespace stiction::nonlinear {

// extra holds entries of rows/cols in [0, n + m): (u, lambda), (lambda, u) and
// (lambda, lambda) blocks; entries inside A's block are added to A's values.
// Every multiplier row gets a diagonal entry (possibly zero) so MatZeroRows and ILU find it.
// tangent.values is consumed (it becomes the result's value array); the caller must hold no
// matrix over it any more. block_size is kept when m is a multiple of it.
Mat build_augmented_matrix(MPI_Comm comm, CsrArrays tangent, PetscInt m, const SparseEntries& extra,
                           PetscInt block_size);

// On several ranks: the distributed tangent (the whole system's size, in the layout's
// numbering, multiplier rows empty) bordered by the entries of extra (app numbering, any
// row; each entry computed on one rank only), as a new MPIAIJ matrix. Entries of another
// rank's rows are sent to it first; each owned row is then the tangent's row merged with
// its compressed constraint entries, read from and written into PETSc's MPIAIJ split
// (diagonal and off-diagonal parts), and the new matrix is made over the merged arrays.
// The tangent is copied: both exist until the caller drops it.
// n_u: the first multiplier unknown (its rows get their diagonal, as above).
Mat build_distributed_augmented_matrix(Mat tangent, const fem::DofLayout& layout, PetscInt n_u,
                                       const SparseEntries& extra, PetscInt block_size);

// A sparse m x m matrix from entries whose indices are already in [0, m); with Keep every
// row has its diagonal (possibly zero), with Omit the pattern is the entries' alone.
enum class Diagonal { Keep, Omit };
Mat build_sparse_matrix(MPI_Comm comm, PetscInt m, const SparseEntries& entries, Diagonal diagonal = Diagonal::Keep);

// The same over the layout's unknowns [first, first + m) (the multipliers), distributed in
// that block's numbering (DofLayout::block_numbering): entries indexed in [0, m), the same
// on every rank, each rank inserting the rows it owns. On one rank build_sparse_matrix.
Mat build_block_matrix(const fem::DofLayout& layout, PetscInt first, PetscInt m, const SparseEntries& entries,
                       Diagonal diagonal = Diagonal::Keep);

}  // namespace stiction::nonlinear
