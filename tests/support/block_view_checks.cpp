#include "support/block_view_checks.hpp"

#include <algorithm>
#include <utility>

#include "block_view.hpp"
#include "hierarchical_pc.hpp"
#include "support/schur_helpers.hpp"

namespace stiction::test {

namespace {

double relative_difference(Vec a, Vec b) {
  PetscVec d;
  VecDuplicate(a, d.out());
  VecWAXPY(d, -1.0, a, b);
  PetscReal nd, na;
  VecNorm(d, NORM_2, &nd);
  VecNorm(a, NORM_2, &na);
  return nd / na;
}

bool is_shell(Mat m) {
  PetscBool shell;
  PetscObjectTypeCompare(reinterpret_cast<PetscObject>(m), MATSHELL, &shell);
  return shell;
}

}  // namespace

ViewAgreement compare_views_with_copies(const nonlinear::NewtonSystem& sys, const std::vector<SorCase>& sweeps) {
  using solvers::block_view;
  IS l = sys.field("u_l")->is, q = sys.field("u_q")->is;
  const solvers::IndexRange lr = solvers::contiguous_range(l), qr = solvers::contiguous_range(q);
  PetscMat qq_view, ql_view, lq_view, qq_copy, ql_copy, lq_copy;
  *qq_view.out() = block_view(sys.matrix, qr, qr);
  *ql_view.out() = block_view(sys.matrix, qr, lr);
  *lq_view.out() = block_view(sys.matrix, lr, qr);
  MatCreateSubMatrix(sys.matrix, q, q, MAT_INITIAL_MATRIX, qq_copy.out());
  MatCreateSubMatrix(sys.matrix, q, l, MAT_INITIAL_MATRIX, ql_copy.out());
  MatCreateSubMatrix(sys.matrix, l, q, MAT_INITIAL_MATRIX, lq_copy.out());
  ViewAgreement agreement;
  agreement.views_are_shells = is_shell(qq_view.get()) && is_shell(ql_view.get()) && is_shell(lq_view.get());
  PetscRandom rng;
  PetscRandomCreate(PetscObjectComm(reinterpret_cast<PetscObject>(sys.matrix.get())), &rng);
  for (auto [view, copy] : {std::pair{qq_view.get(), qq_copy.get()}, std::pair{ql_view.get(), ql_copy.get()},
                            std::pair{lq_view.get(), lq_copy.get()}}) {
    PetscVec x, y_view, y_copy;
    MatCreateVecs(copy, x.out(), y_copy.out());
    VecDuplicate(y_copy, y_view.out());
    VecSetRandom(x, rng);
    MatMult(copy, x, y_copy);
    MatMult(view, x, y_view);
    agreement.product = std::max(agreement.product, relative_difference(y_copy, y_view));
  }
  for (const SorCase& c : sweeps) {
    PetscVec rhs, guess, x_view, x_copy;
    MatCreateVecs(qq_copy, guess.out(), rhs.out());
    VecSetRandom(rhs, rng);
    VecSetRandom(guess, rng);
    VecDuplicate(guess, x_view.out());
    VecDuplicate(guess, x_copy.out());
    VecCopy(guess, x_view);
    VecCopy(guess, x_copy);
    MatSOR(qq_copy, rhs, c.omega, static_cast<MatSORType>(c.flag), c.shift, c.its, c.lits, x_copy);
    const PetscErrorCode err =
        MatSOR(qq_view, rhs, c.omega, static_cast<MatSORType>(c.flag), c.shift, c.its, c.lits, x_view);
    agreement.sweep = std::max(agreement.sweep, err ? 1.0 : relative_difference(x_copy, x_view));
  }
  PetscVec d_view, d_copy;
  MatCreateVecs(qq_copy, d_copy.out(), nullptr);
  VecDuplicate(d_copy, d_view.out());
  MatGetDiagonal(qq_copy, d_copy);
  MatGetDiagonal(qq_view, d_view);
  agreement.diagonal = relative_difference(d_copy, d_view);
  PetscRandomDestroy(&rng);
  return agreement;
}

HierarchicalRun run_hierarchical(const nonlinear::NewtonSystem& sys, const std::string& prefix, bool copies,
                                 const char* lu_package, const char* sweep) {
  const std::string sweep_key = std::string("qq_pc_sor_") + sweep;
  set_options(prefix, {{"ll_ksp_type", "preonly"}, {"ll_pc_type", "lu"}, {"ll_pc_factor_mat_solver_type", lu_package},
                       {"qq_ksp_type", "preonly"}, {"qq_pc_type", "sor"}, {sweep_key.c_str(), nullptr}});
  if (copies) set_options(prefix, {{"block_copies", "true"}});
  solvers::HierarchicalPreconditioner hp(PetscObjectComm(reinterpret_cast<PetscObject>(sys.matrix.get())), prefix);
  hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space, sys.field("u_l")->block_size);
  HierarchicalRun run;
  run.ll_view = is_shell(hp.block(0, 0));
  run.ql_view = is_shell(hp.block(1, 0));
  run.qq_view = is_shell(hp.block(1, 1));
  run.iterations = gmres_iterations(sys, hp, &run.residual);
  return run;
}

}  // namespace stiction::test
