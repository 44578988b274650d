#pragma once
// A block of an AIJ matrix over contiguous row and column ranges, read in place (a MATSHELL
// over the parent's compressed rows): no copy of its entries is made.
//
// The Schur preconditioners extract blocks of the Newton matrix; as copies, the quadratic
// block and its coupling to the linear one (the P2 edge rows) weigh about 70% of the whole
// matrix. What the preconditioner does with them needs only y = B x (the couplings) and, on
// the quadratic block, its diagonal and SOR sweeps (PCSOR, PCJACOBI): a view does both.
// A solver that needs the entries (LU, ILU, AMG) gets a copy instead (block_view_suffices).
#include <initializer_list>
#include <string>

#include "common/petsc.hpp"

namespace stiction::solvers {

// The range [first, first + size) when the index set is exactly that, otherwise size < 0.
struct IndexRange {
  PetscInt first = 0, size = -1;
};
IndexRange contiguous_range(IS is);

// parent: assembled MATSEQAIJ or MATMPIAIJ (kept alive by the view); rows and cols: this
// process's part of the block (contiguous_range of the field's index set), within its own
// rows and columns. A square block (same ranges) supports MatSOR and MatGetDiagonal, every
// block MatMult (and, sequential, MatMultAdd). Collective on an MPI parent.
Mat block_view(Mat parent, IndexRange rows, IndexRange cols);

// Whether block_view can stand for blocks of parent over these ranges on every process (an
// AIJ parent, each range contiguous). Collective, so that all processes choose alike.
bool block_views_possible(Mat parent, std::initializer_list<IndexRange> ranges);

// block_view's two cases: a MATSEQAIJ parent (block_view.cpp), and a MATMPIAIJ parent, read
// through its diagonal and off-process parts (distributed_block_view.cpp).
Mat sequential_block_view(Mat parent, IndexRange rows, IndexRange cols);
Mat distributed_block_view(Mat parent, IndexRange rows, IndexRange cols);

// Whether a preconditioner of this type needs no more of its matrix than a view offers.
bool block_view_suffices(PCType type);

// -<prefix>block_copies (default false): copies instead of views. Views save the memory;
// copies are faster to multiply and sweep (PETSc's inode kernels read compact rows, a view
// skips the other blocks' columns of each row): docs/method.md, "Choices beyond the paper".
bool block_copies_requested(const std::string& prefix);

}  // namespace stiction::solvers
