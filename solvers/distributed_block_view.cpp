// A block of an MPIAIJ matrix read in place. PETSc stores each process's rows as two
// sequential matrices: the diagonal part (its own columns) and the off-process part (the
// columns of other processes, compressed to the ones its rows touch, listed in garray). The
// view is two sequential views over this process's block rows, one of each part, and the
// scatter that brings the other processes' entries of the block's column vector into the
// off-process part's column order (zero where a column lies outside the block). Products
// and sweeps follow MatMult_MPIAIJ and MatSOR_MPIAIJ step for step, so a view gives what a
// copy (MatCreateSubMatrix) of the block gives, up to the order of the off-process sums.
#include <algorithm>
#include <memory>
#include <vector>

#include "block_view.hpp"

namespace stiction::solvers {

namespace {

struct DistributedView {
  PetscMat own, off;  // sequential views of the diagonal and off-process parts
  PetscOwner<VecScatter, VecScatterDestroy> to_ghosts;
  PetscVec ghosts;                // the off-process part's columns (sequential)
  PetscVec b_own, x_own, y_own;   // sequential, over the arrays of the vectors passed in
  PetscVec rhs;                   // SOR's b - (off-process part) x
};

DistributedView& view_of(Mat B) {
  void* ctx;
  MatShellGetContext(B, &ctx);
  return *static_cast<DistributedView*>(ctx);
}

// PETSc's local vector of v in w (sequential, same local size) for the span of a call.
struct LocalPart {
  Vec v, w;
  bool read;
  LocalPart(Vec v_, Vec w_, bool read_) : v(v_), w(w_), read(read_) {
    STICTION_PETSC(read ? VecGetLocalVectorRead(v, w) : VecGetLocalVector(v, w));
  }
  ~LocalPart() { read ? VecRestoreLocalVectorRead(v, w) : VecRestoreLocalVector(v, w); }
};

PetscErrorCode scatter_ghosts(DistributedView& d, Vec x) {
  PetscCall(VecScatterBegin(d.to_ghosts, x, d.ghosts, INSERT_VALUES, SCATTER_FORWARD));
  return VecScatterEnd(d.to_ghosts, x, d.ghosts, INSERT_VALUES, SCATTER_FORWARD);
}

// y = (own part) x + (off-process part) ghosts, as MatMult_MPIAIJ sums.
PetscErrorCode mult(Mat B, Vec x, Vec y) {
  DistributedView& d = view_of(B);
  PetscCall(scatter_ghosts(d, x));
  LocalPart xl(x, d.x_own, true), yl(y, d.y_own, false);
  PetscCall(MatMult(d.own, d.x_own, d.y_own));
  return MatMultAdd(d.off, d.ghosts, d.y_own, d.y_own);
}

PetscErrorCode get_diagonal(Mat B, Vec diag) {
  DistributedView& d = view_of(B);
  LocalPart dl(diag, d.y_own, false);
  return MatGetDiagonal(d.own, d.y_own);
}

// Process-local sweeps as MatSOR_MPIAIJ makes them: the first from a zero guess on the own
// part alone, each later one on b minus the off-process part times the current x.
PetscErrorCode sor(Mat B, Vec b, PetscReal omega, MatSORType flag, PetscReal shift, PetscInt its, PetscInt lits,
                   Vec x) {
  DistributedView& d = view_of(B);
  PetscCheck((flag & SOR_LOCAL_SYMMETRIC_SWEEP) && !(flag & SOR_EISENSTAT), PETSC_COMM_SELF, PETSC_ERR_SUP,
             "distributed block view: only process-local SOR sweeps of a square block");
  const MatSORType later = (flag & SOR_LOCAL_SYMMETRIC_SWEEP) == SOR_LOCAL_SYMMETRIC_SWEEP ? SOR_SYMMETRIC_SWEEP
                           : (flag & SOR_LOCAL_FORWARD_SWEEP)                           ? SOR_FORWARD_SWEEP
                                                                                         : SOR_BACKWARD_SWEEP;
  if (flag & SOR_ZERO_INITIAL_GUESS) {
    LocalPart bl(b, d.b_own, true), xl(x, d.x_own, false);
    PetscCall(MatSOR(d.own, d.b_own, omega, flag, shift, lits, 1, d.x_own));
    --its;
  }
  for (; its > 0; --its) {
    PetscCall(scatter_ghosts(d, x));
    PetscCall(VecScale(d.ghosts, -1.0));
    LocalPart bl(b, d.b_own, true), xl(x, d.x_own, false);
    PetscCall(MatMultAdd(d.off, d.ghosts, d.b_own, d.rhs));
    PetscCall(MatSOR(d.own, d.rhs, omega, later, shift, lits, 1, d.x_own));
  }
  return 0;
}

PetscErrorCode destroy(Mat B) {
  delete &view_of(B);
  return 0;
}

// Where each column of the off-process part (garray: global columns, ascending) sits in the
// block's column vector, numbered process by process: every process's column range, gathered.
void ghost_positions(Mat parent, IndexRange cols, const PetscInt* garray, PetscInt n_ghosts,
                     std::vector<PetscInt>& from, std::vector<PetscInt>& to) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(parent));
  int size;
  MPI_Comm_size(comm, &size);
  const PetscInt mine[2] = {cols.first, cols.size};
  std::vector<PetscInt> all(2 * static_cast<size_t>(size));
  MPI_Allgather(mine, 2, MPIU_INT, all.data(), 2, MPIU_INT, comm);
  std::vector<PetscInt> offset(static_cast<size_t>(size) + 1, 0);
  for (int r = 0; r < size; ++r) offset[r + 1] = offset[r] + all[2 * r + 1];
  const PetscInt* column_ranges;
  STICTION_PETSC(MatGetOwnershipRangesColumn(parent, &column_ranges));
  for (PetscInt k = 0; k < n_ghosts; ++k) {
    const PetscInt c = garray[k];
    const int r = static_cast<int>(std::upper_bound(column_ranges, column_ranges + size + 1, c) - column_ranges) - 1;
    const PetscInt first = all[2 * r], n = all[2 * r + 1];
    if (c < first || c >= first + n) continue;  // outside the block: stays zero
    from.push_back(offset[r] + c - first);
    to.push_back(k);
  }
}

}  // namespace

Mat distributed_block_view(Mat parent, IndexRange rows, IndexRange cols) {
  PetscBool mpi;
  STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(parent), MATMPIAIJ, &mpi));
  PetscInt row_start, row_end, col_start, col_end;
  STICTION_PETSC(MatGetOwnershipRange(parent, &row_start, &row_end));
  STICTION_PETSC(MatGetOwnershipRangeColumn(parent, &col_start, &col_end));
  if (!mpi || rows.size < 0 || cols.size < 0 || rows.first < row_start || rows.first + rows.size > row_end ||
      cols.first < col_start || cols.first + cols.size > col_end)
    throw Error("block view: needs a MATMPIAIJ parent and ranges within this process's rows and columns",
                ErrorKind::Internal);
  Mat own_part, off_part;
  const PetscInt* garray;
  STICTION_PETSC(MatMPIAIJGetSeqAIJ(parent, &own_part, &off_part, &garray));
  PetscInt n_ghosts;
  STICTION_PETSC(MatGetSize(off_part, nullptr, &n_ghosts));
  const IndexRange local_rows{rows.first - row_start, rows.size};
  auto owned = std::make_unique<DistributedView>();
  DistributedView* d = owned.get();
  *d->own.out() = sequential_block_view(own_part, local_rows, {cols.first - col_start, cols.size});
  // Only multiplied, never swept (its column range is not the rows').
  *d->off.out() = sequential_block_view(off_part, local_rows, {0, n_ghosts});
  const bool square = rows.first == cols.first && rows.size == cols.size;

  Mat B;
  STICTION_PETSC(MatCreateShell(PetscObjectComm(reinterpret_cast<PetscObject>(parent)), rows.size, cols.size,
                                PETSC_DETERMINE, PETSC_DETERMINE, owned.release(), &B));
  STICTION_PETSC(MatShellSetOperation(B, MATOP_MULT, reinterpret_cast<void (*)(void)>(mult)));
  STICTION_PETSC(MatShellSetOperation(B, MATOP_DESTROY, reinterpret_cast<void (*)(void)>(destroy)));
  if (square) {
    STICTION_PETSC(MatShellSetOperation(B, MATOP_GET_DIAGONAL, reinterpret_cast<void (*)(void)>(get_diagonal)));
    STICTION_PETSC(MatShellSetOperation(B, MATOP_SOR, reinterpret_cast<void (*)(void)>(sor)));
  }

  std::vector<PetscInt> from, to;
  ghost_positions(parent, cols, garray, n_ghosts, from, to);
  PetscVec x;
  STICTION_PETSC(MatCreateVecs(B, x.out(), nullptr));
  STICTION_PETSC(VecCreateSeq(PETSC_COMM_SELF, n_ghosts, d->ghosts.out()));
  STICTION_PETSC(VecSet(d->ghosts, 0.0));
  PetscIS is_from, is_to;
  STICTION_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(from.size()), from.data(), PETSC_COPY_VALUES,
                                 is_from.out()));
  STICTION_PETSC(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(to.size()), to.data(), PETSC_COPY_VALUES,
                                 is_to.out()));
  STICTION_PETSC(VecScatterCreate(x, is_from, d->ghosts, is_to, d->to_ghosts.out()));
  for (auto [v, n] : {std::pair{&d->b_own, rows.size}, std::pair{&d->y_own, rows.size}, std::pair{&d->x_own, cols.size}})
    STICTION_PETSC(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, n, nullptr, v->out()));
  STICTION_PETSC(VecCreateSeq(PETSC_COMM_SELF, rows.size, d->rhs.out()));
  return B;
}

}  // namespace stiction::solvers
