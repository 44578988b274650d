#include "support/schur_helpers.hpp"

#include <string>

#include "builtin_scenes.hpp"
#include "registry.hpp"

namespace stiction::test {

StepSystem::StepSystem(const std::string& builtin_scene)
    : scene(harness::open_scene(builtin_scene, 0)), lu(solvers::create_solver("lu-mumps", PETSC_COMM_WORLD)) {
  newton = std::make_unique<nonlinear::QuasiStaticSolver>(PETSC_COMM_WORLD, scene->problem, scene->newton, *lu);
  newton->solve_step(1);
}

Mat dense_schur_complement(Mat A, Mat B, Mat C, Mat D) {
  Mat F, Bd, X, CX, S;
  MatFactorInfo info;
  MatFactorInfoInitialize(&info);
  IS rperm, cperm;
  MatGetOrdering(A, MATORDERINGND, &rperm, &cperm);
  MatGetFactor(A, MATSOLVERPETSC, MAT_FACTOR_LU, &F);
  MatLUFactorSymbolic(F, A, rperm, cperm, &info);
  MatLUFactorNumeric(F, A, &info);
  MatConvert(B, MATSEQDENSE, MAT_INITIAL_MATRIX, &Bd);
  MatDuplicate(Bd, MAT_DO_NOT_COPY_VALUES, &X);
  MatMatSolve(F, Bd, X);
  MatMatMult(C, X, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &CX);
  MatConvert(D, MATSEQDENSE, MAT_INITIAL_MATRIX, &S);
  MatAXPY(S, -1.0, CX, SAME_NONZERO_PATTERN);
  for (Mat* m : {&F, &Bd, &X, &CX}) MatDestroy(m);
  ISDestroy(&rperm);
  ISDestroy(&cperm);
  return S;
}

int gmres_iterations(const nonlinear::NewtonSystem& sys, const solvers::ShellPreconditioner& p, double* residual) {
  KSP ksp;
  PC pc;
  Vec x, r;
  KSPCreate(PETSC_COMM_WORLD, &ksp);
  KSPSetOperators(ksp, sys.matrix, sys.matrix);
  KSPSetType(ksp, KSPGMRES);
  KSPSetPCSide(ksp, PC_RIGHT);
  KSPSetTolerances(ksp, 1e-10, 1e-50, 1e10, 200);
  KSPGMRESSetRestart(ksp, 200);
  KSPGetPC(ksp, &pc);
  solvers::use_as_shell(pc, p, "preconditioner under test");
  MatCreateVecs(sys.matrix, &x, &r);
  KSPSolve(ksp, sys.rhs, x);
  PetscInt its;
  KSPGetIterationNumber(ksp, &its);
  PetscReal bnorm, rnorm;
  MatMult(sys.matrix, x, r);
  VecAYPX(r, -1.0, sys.rhs);
  VecNorm(r, NORM_2, &rnorm);
  VecNorm(sys.rhs, NORM_2, &bnorm);
  *residual = rnorm / bnorm;
  VecDestroy(&x);
  VecDestroy(&r);
  KSPDestroy(&ksp);
  return static_cast<int>(its);
}

ExactHierarchical::ExactHierarchical(const nonlinear::NewtonSystem& sys, const std::string& prefix)
    : hp(PETSC_COMM_WORLD, prefix) {
  set_options(prefix, {{"ll_ksp_type", "preonly"}, {"ll_pc_type", "lu"}, {"qq_ksp_type", "preonly"}, {"qq_pc_type", "lu"}});
  hp.set_form(solvers::SchurForm::Full);  // extracts A_lq, needed for S_q
  hp.setup(sys.matrix, sys.field("u_l")->is, sys.field("u_q")->is, sys.near_null_space, sys.field("u_l")->block_size);
  // The blocks as copies (HP may hold views of some, which offer products only).
  IS l = sys.field("u_l")->is, q = sys.field("u_q")->is;
  Mat ll, lq, ql, qq;
  MatCreateSubMatrix(sys.matrix, l, l, MAT_INITIAL_MATRIX, &ll);
  MatCreateSubMatrix(sys.matrix, l, q, MAT_INITIAL_MATRIX, &lq);
  MatCreateSubMatrix(sys.matrix, q, l, MAT_INITIAL_MATRIX, &ql);
  MatCreateSubMatrix(sys.matrix, q, q, MAT_INITIAL_MATRIX, &qq);
  schur = dense_schur_complement(ll, lq, ql, qq);
  for (Mat* m : {&ll, &lq, &ql, &qq}) MatDestroy(m);
  hp.set_quadratic_operator(schur);
}

ExactHierarchical::~ExactHierarchical() { MatDestroy(&schur); }

void set_options(const std::string& prefix, std::initializer_list<std::pair<const char*, const char*>> options) {
  for (const auto& [key, value] : options) PetscOptionsSetValue(nullptr, ("-" + prefix + key).c_str(), value);
}

}  // namespace stiction::test
