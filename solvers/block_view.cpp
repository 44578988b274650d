#include "block_view.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace stiction::solvers {

namespace {

constexpr PetscInt kMaxGroup = 5;  // PETSc's default inode limit

// Consecutive rows with the same columns in the block (the dim rows of one mesh node) form
// a group that the kernels treat together, reading the column indices once, as PETSc's
// inode kernels do. In every row of a group the block's columns start at the same offset
// from the parent row's start; in a square block, row first + g has its diagonal at
// position diagonal + g of those columns (the group's diagonal block).
struct Group {
  PetscInt first = 0, size = 0;  // block rows
  PetscInt offset = 0, length = 0;
  PetscInt diagonal = -1;  // square blocks; -1: some row of the group has no diagonal entry
  PetscInt inverse_at = 0;  // its diagonal block's inverse in View::block_inverse (size^2)
};

struct View {
  Mat parent = nullptr;
  IndexRange rows, cols;
  bool square = false;
  std::vector<Group> groups;
  // SOR: omega / (a_ii + shift) and the groups' diagonal block inverses, computed at the
  // first sweep with these omega and shift and kept (a view's parent does not change while
  // the view is used: the preconditioners make new views at every set-up); lower is work.
  mutable std::vector<PetscScalar> inverse_pivot, block_inverse, lower;
  mutable PetscReal pivots_omega = 0, pivots_shift = 0;
  mutable bool pivots_ready = false;
};

// The parent's compressed rows (valid while the parent is unchanged).
struct Rows {
  const PetscInt *ia = nullptr, *ja = nullptr;
  const PetscScalar* a = nullptr;
};

PetscErrorCode get_rows(Mat parent, Rows& r) {
  PetscInt n;
  PetscBool done;
  PetscCall(MatGetRowIJ(parent, 0, PETSC_FALSE, PETSC_FALSE, &n, &r.ia, &r.ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "block view: the parent is not an AIJ matrix");
  return MatSeqAIJGetArrayRead(parent, &r.a);
}

PetscErrorCode restore_rows(Mat parent, Rows& r) {
  PetscInt n;
  PetscBool done;
  PetscCall(MatSeqAIJRestoreArrayRead(parent, &r.a));
  return MatRestoreRowIJ(parent, 0, PETSC_FALSE, PETSC_FALSE, &n, &r.ia, &r.ja, &done);
}

const View& view_of(Mat B) {
  void* ctx;
  MatShellGetContext(B, &ctx);
  return *static_cast<const View*>(ctx);
}

// A group's entries in the parent's arrays.
template <int G>
struct GroupRows {
  const PetscInt* cols;
  const PetscScalar* a[G];
  GroupRows(const View& v, const Rows& r, const Group& grp) {
    const PetscInt row = v.rows.first + grp.first;
    cols = r.ja + r.ia[row] + grp.offset;
    for (int g = 0; g < G; ++g) a[g] = r.a + r.ia[row + g] + grp.offset;
  }
  // sum[g] -= sum_k a_g[k] x(cols[k]) over positions [from, to).
  void subtract(PetscInt from, PetscInt to, const PetscScalar* xc, PetscScalar* sum) const {
    for (PetscInt k = from; k < to; ++k) {
      const PetscScalar xk = xc[cols[k]];
      for (int g = 0; g < G; ++g) sum[g] -= a[g][k] * xk;
    }
  }
};

// F<group size>::run(group, args...): the kernels are compiled per group size.
template <template <int> class F, class... Args>
auto dispatch(const Group& grp, Args&&... args) {
  switch (grp.size) {
    case 1: return F<1>::run(grp, args...);
    case 2: return F<2>::run(grp, args...);
    case 3: return F<3>::run(grp, args...);
    case 4: return F<4>::run(grp, args...);
    default: return F<5>::run(grp, args...);
  }
}

// dispatch for every group, in order or in reverse.
template <template <int> class F, class... Args>
void for_groups(const View& v, bool reverse, Args&&... args) {
  const size_t n = v.groups.size();
  for (size_t q = 0; q < n; ++q) dispatch<F>(v.groups[reverse ? n - 1 - q : q], args...);
}

// z = y + B x (y null: z = B x), each row's sum accumulated from y_i in column order as
// PETSc's MatMultAdd_SeqAIJ does (negating a sum is exact, so -(-y - a x) rounds the same).
template <int G>
struct MultAdd {
  static void run(const Group& grp, const View& v, const Rows& r, const PetscScalar* xc, const PetscScalar* y,
                  PetscScalar* z) {
    PetscScalar sum[G];
    for (int g = 0; g < G; ++g) sum[g] = y ? -y[grp.first + g] : 0.0;
    GroupRows<G>(v, r, grp).subtract(0, grp.length, xc, sum);
    for (int g = 0; g < G; ++g) z[grp.first + g] = -sum[g];
  }
};

PetscErrorCode mult_add(Mat B, Vec x, Vec y, Vec z) {
  const View& v = view_of(B);
  Rows r;
  PetscCall(get_rows(v.parent, r));
  const PetscScalar *xa, *ya = nullptr;
  PetscScalar* za;
  PetscCall(VecGetArrayRead(x, &xa));
  if (y && y != z) PetscCall(VecGetArrayRead(y, &ya));
  PetscCall(y == z ? VecGetArray(z, &za) : VecGetArrayWrite(z, &za));
  if (y == z) ya = za;  // each row reads its own y_i before writing z_i
  for_groups<MultAdd>(v, false, v, r, xa - v.cols.first, ya, za);  // x indexed by parent column
  PetscCall(y == z ? VecRestoreArray(z, &za) : VecRestoreArrayWrite(z, &za));
  if (y && y != z) PetscCall(VecRestoreArrayRead(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  return restore_rows(v.parent, r);
}

PetscErrorCode mult(Mat B, Vec x, Vec y) { return mult_add(B, x, nullptr, y); }

PetscErrorCode get_diagonal(Mat B, Vec d) {
  const View& v = view_of(B);
  Rows r;
  PetscCall(get_rows(v.parent, r));
  PetscScalar* da;
  PetscCall(VecGetArrayWrite(d, &da));
  for (const Group& grp : v.groups)
    for (PetscInt g = 0; g < grp.size; ++g)
      da[grp.first + g] =
          grp.diagonal < 0 ? 0.0 : r.a[r.ia[v.rows.first + grp.first + g] + grp.offset + grp.diagonal + g];
  PetscCall(VecRestoreArrayWrite(d, &da));
  return restore_rows(v.parent, r);
}

// What a sweep reads and writes. inverse_pivot holds omega / (a_ii + shift); lower holds,
// after a forward sweep from a zero guess, b minus the lower part at the forward values.
struct Sweep {
  const View& v;
  const Rows& r;
  const PetscScalar* b;
  PetscScalar* x;   // block numbering
  PetscScalar* xc;  // parent column numbering (x - cols.first)
  PetscScalar* inverse_pivot;
  PetscScalar* lower;
  PetscReal omega;
  const PetscScalar* block_inverse;  // non-null: block Gauss-Seidel over the groups
  // x(group) = D^-1 sum, D the group's diagonal block.
  template <int G>
  void solve_block(const Group& grp, const PetscScalar* sum) const {
    const PetscScalar* inv = block_inverse + grp.inverse_at;
    for (int g = 0; g < G; ++g) {
      PetscScalar value = 0;
      for (int h = 0; h < G; ++h) value += inv[g * G + h] * sum[h];
      x[grp.first + g] = value;
    }
  }
};

// The inverse of a group's diagonal block into View::block_inverse; false when singular.
template <int G>
struct InvertBlock {
  static bool run(const Group& grp, const View& v, const Rows& r) {
    Eigen::Matrix<double, G, G> d;
    for (int g = 0; g < G; ++g)
      for (int h = 0; h < G; ++h) d(g, h) = r.a[r.ia[v.rows.first + grp.first + g] + grp.offset + grp.diagonal + h];
    const double det = d.determinant();
    if (!(std::abs(det) > 0) || !std::isfinite(det)) return false;
    Eigen::Map<Eigen::Matrix<double, G, G, Eigen::RowMajor>>(v.block_inverse.data() + grp.inverse_at) = d.inverse();
    return true;
  }
};

PetscErrorCode compute_pivots(const View& v, const Rows& r, PetscReal omega, PetscReal shift, bool block) {
  v.inverse_pivot.resize(static_cast<size_t>(v.rows.size));
  v.lower.resize(static_cast<size_t>(v.rows.size));
  if (block && !v.groups.empty())
    v.block_inverse.resize(static_cast<size_t>(v.groups.back().inverse_at + v.groups.back().size * v.groups.back().size));
  for (const Group& grp : v.groups) {
    PetscCheck(grp.diagonal >= 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE,
               "block view: a row of the block from %" PetscInt_FMT " has no diagonal entry", grp.first);
    for (PetscInt g = 0; g < grp.size; ++g)
      v.inverse_pivot[grp.first + g] =
          omega / (r.a[r.ia[v.rows.first + grp.first + g] + grp.offset + grp.diagonal + g] + shift);
    if (!block) continue;
    const bool ok = dispatch<InvertBlock>(grp, v, r);
    PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_MAT_LU_ZRPVT, "block view: the diagonal block at row %" PetscInt_FMT " is singular",
               grp.first);
  }
  return 0;
}

template <int G>
struct Forward {
  // zero: x is zero from this group on (the first sweep of a zero initial guess): only the
  // lower part is read.
  static void run(const Group& grp, const Sweep& s, bool zero) {
    const GroupRows<G> rows(s.v, s.r, grp);
    const PetscInt k0 = grp.diagonal, i0 = grp.first;
    PetscScalar sum[G];
    for (int g = 0; g < G; ++g) sum[g] = s.b[i0 + g];
    rows.subtract(0, k0, s.xc, sum);
    if (!zero) rows.subtract(k0 + G, grp.length, s.xc, sum);
    if (s.block_inverse) {
      if (zero)
        for (int g = 0; g < G; ++g) s.lower[i0 + g] = sum[g];
      s.template solve_block<G>(grp, sum);
      return;
    }
    for (int g = 0; g < G; ++g) {
      PetscScalar t = sum[g];
      for (int h = 0; h < G; ++h)
        if (h != g && (!zero || h < g)) t -= rows.a[g][k0 + h] * s.x[i0 + h];
      if (zero) {
        s.lower[i0 + g] = t;
        s.x[i0 + g] = t * s.inverse_pivot[i0 + g];
      } else {
        s.x[i0 + g] = (1 - s.omega) * s.x[i0 + g] + t * s.inverse_pivot[i0 + g];
      }
    }
  }
};

template <int G>
struct Backward {
  // after_zero: the forward sweep before it started from zero; only the upper part is read.
  static void run(const Group& grp, const Sweep& s, bool after_zero) {
    const GroupRows<G> rows(s.v, s.r, grp);
    const PetscInt k0 = grp.diagonal, i0 = grp.first;
    PetscScalar sum[G];
    for (int g = 0; g < G; ++g) sum[g] = after_zero ? s.lower[i0 + g] : s.b[i0 + g];
    if (!after_zero) rows.subtract(0, k0, s.xc, sum);
    rows.subtract(k0 + G, grp.length, s.xc, sum);
    if (s.block_inverse) {
      s.template solve_block<G>(grp, sum);
      return;
    }
    for (int g = G - 1; g >= 0; --g) {
      PetscScalar t = sum[g];
      for (int h = 0; h < G; ++h)
        if (h != g && (!after_zero || h > g)) t -= rows.a[g][k0 + h] * s.x[i0 + h];
      s.x[i0 + g] = (1 - s.omega) * s.x[i0 + g] + t * s.inverse_pivot[i0 + g];
    }
  }
};

// SOR sweeps as PETSc's MatSOR defines them for an AIJ matrix with inodes: with omega = 1
// and no shift, block Gauss-Seidel over the groups (each group's diagonal block solved
// exactly, as MatSOR_SeqAIJ_Inode does); otherwise point SOR (MatSOR_SeqAIJ). With a zero
// initial guess, the first forward sweep reads only the lower part, and a following
// backward sweep reuses b minus that lower part (the same sums, half the work).
PetscErrorCode sor(Mat B, Vec b, PetscReal omega, MatSORType flag, PetscReal shift, PetscInt its, PetscInt lits,
                   Vec x) {
  const View& v = view_of(B);
  PetscCheck(!(flag & SOR_EISENSTAT), PETSC_COMM_SELF, PETSC_ERR_SUP, "block view: no Eisenstat SOR");
  PetscCheck(v.square, PETSC_COMM_SELF, PETSC_ERR_SUP, "block view: SOR needs a square block");
  const bool forward = flag & (SOR_FORWARD_SWEEP | SOR_LOCAL_FORWARD_SWEEP);
  const bool backward = flag & (SOR_BACKWARD_SWEEP | SOR_LOCAL_BACKWARD_SWEEP);
  const PetscInt m = v.rows.size;
  Rows r;
  PetscCall(get_rows(v.parent, r));
  const bool block = omega == 1.0 && shift == 0.0;
  if (!v.pivots_ready || v.pivots_omega != omega || v.pivots_shift != shift) {
    PetscCall(compute_pivots(v, r, omega, shift, block));
    v.pivots_ready = true, v.pivots_omega = omega, v.pivots_shift = shift;
  }
  const PetscScalar* ba;
  PetscScalar* xa;
  PetscCall(VecGetArrayRead(b, &ba));
  PetscCall(VecGetArray(x, &xa));
  const Sweep s{v, r, ba, xa, xa - v.cols.first, v.inverse_pivot.data(), v.lower.data(), omega,
                block ? v.block_inverse.data() : nullptr};
  bool zero = flag & SOR_ZERO_INITIAL_GUESS;
  if (zero && !forward) std::fill(xa, xa + m, 0.0);  // a backward sweep reads all of x
  for (PetscInt sweep = 0; sweep < its * lits; ++sweep) {
    bool after_zero = false;
    if (forward) {
      for_groups<Forward>(v, false, s, zero);
      after_zero = zero;
    }
    if (backward) for_groups<Backward>(v, true, s, after_zero);
    zero = false;
  }
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(VecRestoreArrayRead(b, &ba));
  return restore_rows(v.parent, r);
}

PetscErrorCode destroy(Mat B) {
  void* ctx;
  PetscCall(MatShellGetContext(B, &ctx));
  auto* v = static_cast<View*>(ctx);
  PetscCall(MatDestroy(&v->parent));
  delete v;
  return 0;
}

}  // namespace

IndexRange contiguous_range(IS is) {
  PetscInt n;
  const PetscInt* idx;
  STICTION_PETSC(ISGetLocalSize(is, &n));
  STICTION_PETSC(ISGetIndices(is, &idx));
  IndexRange range{n > 0 ? idx[0] : 0, n};
  for (PetscInt k = 0; k < n && range.size >= 0; ++k)
    if (idx[k] != range.first + k) range.size = -1;
  STICTION_PETSC(ISRestoreIndices(is, &idx));
  return range;
}

Mat block_view(Mat parent, IndexRange rows, IndexRange cols) {
  PetscBool mpi;
  STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(parent), MATMPIAIJ, &mpi));
  return mpi ? distributed_block_view(parent, rows, cols) : sequential_block_view(parent, rows, cols);
}

bool block_views_possible(Mat parent, std::initializer_list<IndexRange> ranges) {
  PetscBool seq, mpi;
  STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(parent), MATSEQAIJ, &seq));
  STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(parent), MATMPIAIJ, &mpi));
  int possible = seq || mpi;
  for (const IndexRange& r : ranges) possible = possible && r.size >= 0;
  MPI_Allreduce(MPI_IN_PLACE, &possible, 1, MPI_INT, MPI_LAND, PetscObjectComm(reinterpret_cast<PetscObject>(parent)));
  return possible;
}

Mat sequential_block_view(Mat parent, IndexRange rows, IndexRange cols) {
  PetscBool seq;
  STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(parent), MATSEQAIJ, &seq));
  if (!seq || rows.size < 0 || cols.size < 0) throw Error("block view: needs a MATSEQAIJ parent and contiguous ranges", ErrorKind::Internal);
  auto* v = new View{parent, rows, cols, rows.first == cols.first && rows.size == cols.size, {}, {}, {}};
  Rows r;
  STICTION_PETSC(get_rows(parent, r));
  // Each row's block columns: [first, first + length) of the parent row, and the diagonal's
  // position among them (square blocks), then rows grouped as described at Group.
  for (PetscInt i = 0; i < rows.size; ++i) {
    const PetscInt row = rows.first + i;
    const PetscInt* row_first = r.ja + r.ia[row];
    const PetscInt* row_last = r.ja + r.ia[row + 1];
    const PetscInt* first = std::lower_bound(row_first, row_last, cols.first);
    const PetscInt* last = std::lower_bound(first, row_last, cols.first + cols.size);
    PetscInt diagonal = -1;
    if (v->square) {
      const PetscInt* d = std::lower_bound(first, last, row);
      if (d != last && *d == row) diagonal = static_cast<PetscInt>(d - first);
    }
    const Group here{i, 1, static_cast<PetscInt>(first - row_first), static_cast<PetscInt>(last - first), diagonal, 0};
    if (!v->groups.empty()) {
      Group& prev = v->groups.back();
      const PetscInt* prev_cols = r.ja + r.ia[rows.first + prev.first] + prev.offset;
      const bool same = prev.size < kMaxGroup && prev.length == here.length && std::equal(first, last, prev_cols);
      const bool diagonal_block = !v->square || (prev.diagonal >= 0 && diagonal == prev.diagonal + prev.size);
      if (same && diagonal_block) {
        ++prev.size;
        continue;
      }
    }
    v->groups.push_back(here);
  }
  STICTION_PETSC(restore_rows(parent, r));
  for (size_t k = 1; k < v->groups.size(); ++k)
    v->groups[k].inverse_at = v->groups[k - 1].inverse_at + v->groups[k - 1].size * v->groups[k - 1].size;
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(parent)));
  Mat B;
  STICTION_PETSC(MatCreateShell(PetscObjectComm(reinterpret_cast<PetscObject>(parent)), rows.size, cols.size,
                                rows.size, cols.size, v, &B));
  STICTION_PETSC(MatShellSetOperation(B, MATOP_MULT, reinterpret_cast<void (*)(void)>(mult)));
  STICTION_PETSC(MatShellSetOperation(B, MATOP_MULT_ADD, reinterpret_cast<void (*)(void)>(mult_add)));
  STICTION_PETSC(MatShellSetOperation(B, MATOP_DESTROY, reinterpret_cast<void (*)(void)>(destroy)));
  if (v->square) {
    STICTION_PETSC(MatShellSetOperation(B, MATOP_GET_DIAGONAL, reinterpret_cast<void (*)(void)>(get_diagonal)));
    STICTION_PETSC(MatShellSetOperation(B, MATOP_SOR, reinterpret_cast<void (*)(void)>(sor)));
  }
  return B;
}

bool block_copies_requested(const std::string& prefix) {
  PetscBool copies = PETSC_FALSE, set;
  STICTION_PETSC(PetscOptionsGetBool(nullptr, prefix.c_str(), "-block_copies", &copies, &set));
  return copies;
}

bool block_view_suffices(PCType type) {
  for (const char* t : {PCSOR, PCJACOBI, PCNONE})
    if (std::strcmp(type, t) == 0) return true;
  return false;
}

}  // namespace stiction::solvers
