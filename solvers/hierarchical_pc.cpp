#include "hierarchical_pc.hpp"

#include <fmt/format.h>

#include "block_view.hpp"
#include "common/error.hpp"
#include "solver_figures.hpp"

#include <vector>

namespace stiction::solvers {

namespace {

// The rigid-body modes restricted to u_l (for the hierarchical basis these are exactly the
// P1 modes), orthonormalised as MatNullSpaceCreate requires.
MatNullSpace restrict_modes(MatNullSpace full, IS is) {
  PetscBool has_constant;
  PetscInt n;
  const Vec* vecs;
  STICTION_PETSC(MatNullSpaceGetVecs(full, &has_constant, &n, &vecs));
  std::vector<Vec> sub(n);
  for (PetscInt i = 0; i < n; ++i) {
    Vec view;
    STICTION_PETSC(VecGetSubVector(vecs[i], is, &view));
    STICTION_PETSC(VecDuplicate(view, &sub[i]));
    STICTION_PETSC(VecCopy(view, sub[i]));
    STICTION_PETSC(VecRestoreSubVector(vecs[i], is, &view));
    for (PetscInt j = 0; j < i; ++j) {
      PetscScalar dot;
      STICTION_PETSC(VecDot(sub[i], sub[j], &dot));
      STICTION_PETSC(VecAXPY(sub[i], -dot, sub[j]));
    }
    STICTION_PETSC(VecNormalize(sub[i], nullptr));
  }
  MatNullSpace nsp;
  STICTION_PETSC(MatNullSpaceCreate(PetscObjectComm(reinterpret_cast<PetscObject>(full)), PETSC_FALSE, n, sub.data(), &nsp));
  for (Vec& v : sub) VecDestroy(&v);
  return nsp;
}

PetscErrorCode shell_apply(PC pc, Vec r, Vec x) {
  void* ctx;
  PetscCall(PCShellGetContext(pc, &ctx));
  try {
    static_cast<const ShellPreconditioner*>(ctx)->apply(r, x);
  } catch (const std::exception& e) {
    SETERRQ(PetscObjectComm(reinterpret_cast<PetscObject>(pc)), PETSC_ERR_LIB, "%s", e.what());
  }
  return 0;
}

// A fresh inner solver under the options prefix <prefix><block>_.
void create_block_solver(MPI_Comm comm, const std::string& prefix, const char* block, PetscKSP& ksp) {
  STICTION_PETSC(KSPCreate(comm, ksp.out()));
  STICTION_PETSC(KSPSetOptionsPrefix(ksp, (prefix + block + "_").c_str()));
}

}  // namespace

SchurForm schur_form_from_options(const std::string& prefix, const char* key, SchurFormChoice first,
                                  SchurFormChoice second, SchurForm current) {
  char value[16] = "";
  PetscBool set = PETSC_FALSE;
  STICTION_PETSC(PetscOptionsGetString(nullptr, prefix.c_str(), (std::string("-") + key).c_str(), value,
                                       sizeof value, &set));
  if (!set) return current;
  const std::string v = value;
  if (v == first.name) return first.form;
  if (v == second.name) return second.form;
  throw Error(fmt::format("-{}{}: '{}' is neither {} nor {}", prefix, key, v, first.name, second.name));
}

HierarchicalPreconditioner::HierarchicalPreconditioner(MPI_Comm comm, const std::string& prefix) : prefix_(prefix) {
  create_block_solver(comm, prefix, "ll", ksp_ll_);
  create_block_solver(comm, prefix, "qq", ksp_qq_);
}

void HierarchicalPreconditioner::setup(Mat A, IS linear, IS quadratic, MatNullSpace near_null_space, int block_size) {
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(linear)));
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(quadratic)));
  *is_l_.out() = linear;
  *is_q_.out() = quadratic;
  form_ = schur_form_from_options(prefix_, "hp_fact", {"lower", SchurForm::Lower}, {"full", SchurForm::Full}, form_);
  // The qq solver's options first: whether its preconditioner can work on a view of A_qq.
  STICTION_PETSC(KSPSetFromOptions(ksp_qq_));
  PC pc_qq;
  PCType qq_type;
  STICTION_PETSC(KSPGetPC(ksp_qq_, &pc_qq));
  STICTION_PETSC(PCGetType(pc_qq, &qq_type));
  const IndexRange l = contiguous_range(linear), q = contiguous_range(quadratic);
  const bool views = block_views_possible(A, {l, q}) && !block_copies_requested(prefix_);
  // Copies are reused while the pattern is unchanged (every Newton step without contact;
  // a contact system's pattern moves with the projections); views are made afresh, cheaply.
  const bool same_pattern = pattern_ == pattern_key(A);
  pattern_ = pattern_key(A);
  auto take_block = [&](PetscMat& held, IS rows, IS cols, IndexRange r, IndexRange c, bool view) {
    if (view) {
      *held.out() = block_view(A, r, c);
      return;
    }
    PetscBool is_shell = PETSC_FALSE;
    if (held) STICTION_PETSC(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(held.get()), MATSHELL, &is_shell));
    const bool reuse = held && same_pattern && !is_shell;
    Mat m = reuse ? held.get() : nullptr;
    STICTION_PETSC(MatCreateSubMatrix(A, rows, cols, reuse ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &m));
    if (!reuse) *held.out() = m;
  };
  take_block(A_ll_, linear, linear, l, l, false);  // AMG and LU need its entries
  take_block(A_ql_, quadratic, linear, q, l, views);
  take_block(A_qq_, quadratic, quadratic, q, q, views && qq_type && block_view_suffices(qq_type));
  if (form_ == SchurForm::Full) take_block(A_lq_, linear, quadratic, l, q, views);
  STICTION_PETSC(MatSetBlockSize(A_ll_, block_size));  // hypre's nodal coarsening needs it
  if (near_null_space) {
    PetscNullSpace sub(restrict_modes(near_null_space, linear));
    STICTION_PETSC(MatSetNearNullSpace(A_ll_, sub));
  }
  STICTION_PETSC(KSPSetOperators(ksp_ll_, A_ll_, A_ll_));
  STICTION_PETSC(KSPSetOperators(ksp_qq_, A_qq_, A_qq_));
  for (KSP k : {ksp_ll_.get(), ksp_qq_.get()}) {
    STICTION_PETSC(KSPSetFromOptions(k));
    STICTION_PETSC(KSPSetUp(k));
  }
  if (!work_q_) {
    STICTION_PETSC(MatCreateVecs(A_qq_, work_q_.out(), nullptr));
    STICTION_PETSC(MatCreateVecs(A_ll_, work_l_.out(), work_l2_.out()));
  }
}

void HierarchicalPreconditioner::release() {
  // The linear block's solver is made afresh rather than reset: PETSc 3.18's GAMG, after
  // KSPReset, keeps its coarse levels' operators and refuses the next set-up once the new
  // A_ll aggregates to other sizes ("Cannot change local size of Amat after use": schur-gamg
  // on ironing-2d, the third load step).
  create_block_solver(PetscObjectComm(reinterpret_cast<PetscObject>(ksp_ll_.get())), prefix_, "ll", ksp_ll_);
  STICTION_PETSC(KSPReset(ksp_qq_));
  A_ll_.reset(), A_lq_.reset(), A_ql_.reset(), A_qq_.reset();
  pattern_ = {};
}

void HierarchicalPreconditioner::set_quadratic_operator(Mat S) {
  STICTION_PETSC(KSPSetOperators(ksp_qq_, S, S));
  STICTION_PETSC(KSPSetUp(ksp_qq_));
}

double HierarchicalPreconditioner::copied_blocks_mb() const {
  return aij_storage_mb(A_ll_) + aij_storage_mb(A_lq_) + aij_storage_mb(A_ql_) + aij_storage_mb(A_qq_);
}

Mat HierarchicalPreconditioner::block(int row, int col) const {
  if (row == 0) return col == 0 ? A_ll_.get() : A_lq_.get();
  return col == 0 ? A_ql_.get() : A_qq_.get();
}

void HierarchicalPreconditioner::apply(Vec r, Vec x) const {
  Vec rl, rq, xl, xq;
  STICTION_PETSC(VecGetSubVector(r, is_l_, &rl));
  STICTION_PETSC(VecGetSubVector(r, is_q_, &rq));
  STICTION_PETSC(VecGetSubVector(x, is_l_, &xl));
  STICTION_PETSC(VecGetSubVector(x, is_q_, &xq));
  Vec yl = form_ == SchurForm::Full ? work_l_.get() : xl;
  STICTION_PETSC(KSPSolve(ksp_ll_, rl, yl));                 // y_l = A_ll^-1 r_l
  STICTION_PETSC(MatMult(A_ql_, yl, work_q_));
  STICTION_PETSC(VecAYPX(work_q_, -1.0, rq));                // r_q - A_ql y_l
  STICTION_PETSC(KSPSolve(ksp_qq_, work_q_, xq));            // x_q = S~^-1 (...)
  if (form_ == SchurForm::Full) {
    STICTION_PETSC(MatMult(A_lq_, xq, work_l2_));
    STICTION_PETSC(VecAYPX(work_l2_, -1.0, rl));             // r_l - A_lq x_q
    STICTION_PETSC(KSPSolve(ksp_ll_, work_l2_, xl));         // x_l = A_ll^-1 (...)
  }
  STICTION_PETSC(VecRestoreSubVector(x, is_q_, &xq));
  STICTION_PETSC(VecRestoreSubVector(x, is_l_, &xl));
  STICTION_PETSC(VecRestoreSubVector(r, is_q_, &rq));
  STICTION_PETSC(VecRestoreSubVector(r, is_l_, &rl));
}

void use_as_shell(PC pc, const ShellPreconditioner& p, const char* name) {
  STICTION_PETSC(PCSetType(pc, PCSHELL));
  STICTION_PETSC(PCShellSetContext(pc, const_cast<ShellPreconditioner*>(&p)));
  STICTION_PETSC(PCShellSetApply(pc, shell_apply));
  STICTION_PETSC(PCShellSetName(pc, name));
}

}  // namespace stiction::solvers
