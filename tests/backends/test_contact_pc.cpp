// The global contact level (33): with the exact inverse of the displacement block inside
// and the exact Schur complement S_g = D - B2 A^-1 B1, the four-factor form is the exact
// inverse of the contact system (30): GMRES converges in one iteration.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "builtin_scenes.hpp"
#include "contact_pc.hpp"
#include "ksp_solver.hpp"
#include "registry.hpp"
#include "multiplier_schur_parts.hpp"
#include "support/schur_helpers.hpp"

namespace stiction::test {
namespace {

// The exact S_g = D - B2 A^-1 B1 of the contact system, from the blocks cp extracted (dense).
Mat exact_contact_schur(const nonlinear::NewtonSystem& sys, const solvers::ContactPreconditioner& cp) {
  PetscInt first;
  ISGetMinMax(sys.field("lambda")->is, &first, nullptr);
  IS is_a;
  ISCreateStride(PETSC_COMM_WORLD, first, 0, 1, &is_a);
  Mat A;
  MatCreateSubMatrix(sys.matrix, is_a, is_a, MAT_INITIAL_MATRIX, &A);
  Mat S = dense_schur_complement(A, cp.block(0, 1), cp.block(1, 0), cp.block(1, 1));
  MatDestroy(&A);
  ISDestroy(&is_a);
  return S;
}

TEST(ContactPreconditioner, ExactSubSolvesGiveTheExactInverse) {
  StepSystem step("hertz-cylinder-2d");
  const auto& sys = step.system();
  const auto* lambda = sys.field("lambda");
  ASSERT_NE(lambda, nullptr);
  ExactHierarchical exact(sys, "test_cpc_hp_");
  set_options("test_cpc_", {{"ss_ksp_type", "preonly"}, {"ss_pc_type", "lu"}, {"contact_fact", "full"}});
  solvers::ContactPreconditioner cp(PETSC_COMM_WORLD, "test_cpc_");
  cp.setup(sys.matrix, lambda->is, sys.multiplier_surface, exact.hp);
  // The automatic scale is the geometric mean of the element-end and body-end compliances,
  // and the body's smooth modes are far more compliant than one surface element.
  const auto estimates = cp.scale_estimates();
  EXPECT_GT(estimates.diagonal, 0);
  EXPECT_GT(estimates.smooth, 10 * estimates.diagonal);
  EXPECT_NEAR(cp.scale(), std::sqrt(estimates.diagonal * estimates.smooth), 1e-12 * cp.scale());

  // Approximate S~ (32) first: a working preconditioner, but not exact.
  double residual = 0;
  const int approximate = gmres_iterations(sys, cp, &residual);
  EXPECT_LT(residual, 1e-9);

  Mat S = exact_contact_schur(sys, cp);
  cp.set_schur_operator(S);
  const int iterations = gmres_iterations(sys, cp, &residual);
  EXPECT_EQ(iterations, 1);
  EXPECT_LT(residual, 1e-9);
  EXPECT_GT(approximate, iterations);
  std::printf("contact level: %d GMRES iterations with the default S~, %d with the exact S_g\n", approximate,
              iterations);
  // The block-triangular forms with the exact blocks: M P^-1 - I is nilpotent of degree 2,
  // so GMRES converges in at most two iterations (one when the right side has no
  // displacement part, as after a converged load step's last update).
  for (const char* fact : {"upper", "lower"}) {
    set_options("test_cpc_", {{"contact_fact", fact}});
    cp.setup(sys.matrix, lambda->is, sys.multiplier_surface, exact.hp);
    cp.set_schur_operator(S);
    EXPECT_LE(gmres_iterations(sys, cp, &residual), 2) << fact;
    EXPECT_LT(residual, 1e-9) << fact;
  }
  MatDestroy(&S);
}

Eigen::MatrixXd to_dense(Mat m) {
  PetscInt rows, cols;
  MatGetSize(m, &rows, &cols);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(rows, cols);
  for (PetscInt i = 0; i < rows; ++i) {
    PetscInt n;
    const PetscInt* c;
    const PetscScalar* v;
    MatGetRow(m, i, &n, &c, &v);
    for (PetscInt k = 0; k < n; ++k) d(i, c[k]) = v[k];
    MatRestoreRow(m, i, &n, &c, &v);
  }
  return d;
}

// The parts of (32) formed by sparse products on the surface matrices equal the dense
// products Pi M Pi, Pi K Pi and (dc/dS) M A, on a system with sticking, slipping and
// inactive nodes (cattaneo-mindlin-2d, level 0, the last system of the third load step:
// a stick zone inside a slip annulus).
TEST(MultiplierSchurParts, SparseProductsEqualTheDenseProjections) {
  StepSystem step("cattaneo-mindlin-2d");
  step.newton->solve_step(2);
  step.newton->solve_step(3);
  const nonlinear::MultiplierSurface& surface = step.system().multiplier_surface;
  const solvers::MultiplierSchurParts parts = solvers::form_multiplier_schur_parts(surface);
  const Eigen::MatrixXd M = to_dense(surface.mass), K = to_dense(surface.laplacian), P = to_dense(surface.projector);
  const Eigen::MatrixXd slip = to_dense(surface.slip_rows), A = to_dense(surface.constrained);
  ASSERT_GT(slip.cwiseAbs().sum(), 0);  // some node slips with friction
  ASSERT_LT(A.trace(), A.rows());       // some node is inactive
  const double tolerance = 1e-14;
  EXPECT_LE((to_dense(parts.mass) - P * M * P).cwiseAbs().maxCoeff(), tolerance * M.cwiseAbs().maxCoeff());
  EXPECT_LE((to_dense(parts.laplacian) - P * K * P).cwiseAbs().maxCoeff(), tolerance * K.cwiseAbs().maxCoeff());
  const Eigen::MatrixXd coupling = slip * M * A;
  EXPECT_LE((to_dense(parts.slip_coupling) - coupling).cwiseAbs().maxCoeff(),
            tolerance * coupling.cwiseAbs().maxCoeff());
}

// max |mu| / min |mu| over the eigenvalues mu of S~^-1 S_g on the constrained rows: 1 for
// an exact Schur approximation, the wider the worse GMRES does.
double spectral_spread(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& approximate, const std::vector<int>& rows) {
  const Eigen::Index n = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd Sg(n, n), St(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) Sg(i, j) = exact(rows[i], rows[j]), St(i, j) = approximate(rows[i], rows[j]);
  const Eigen::VectorXd mu = Eigen::EigenSolver<Eigen::MatrixXd>(St.lu().solve(Sg)).eigenvalues().cwiseAbs();
  return mu.maxCoeff() / mu.minCoeff();
}

// The fractional model (solvers/fractional_schur.hpp) against the paper's scaled mass (32)
// on the same Newton system (hertz-cylinder-2d, level 0, exact inner solves so only S~
// differs): the eigenvalues of S~^-1 S_g on the constrained rows spread less, and GMRES
// needs fewer iterations. Both fits hold by construction: g(mu_max) = the element-end
// estimate, the Rayleigh quotient on the smooth probe = the body-end estimate.
TEST(ContactPreconditioner, FractionalModelFollowsTheSchurComplementBetterThanTheMass) {
  StepSystem step("hertz-cylinder-2d");
  const auto& sys = step.system();
  const auto* lambda = sys.field("lambda");
  ASSERT_NE(lambda, nullptr);
  ExactHierarchical exact(sys, "test_frac_hp_");
  const Eigen::MatrixXd mass = to_dense(solvers::form_multiplier_schur_parts(sys.multiplier_surface).mass);
  std::vector<int> constrained;  // the constrained directions: Pi M Pi's non-zero diagonal
  for (Eigen::Index i = 0; i < mass.rows(); ++i)
    if (mass(i, i) > 0) constrained.push_back(static_cast<int>(i));
  ASSERT_GE(constrained.size(), 3u);

  Eigen::MatrixXd exact_schur;  // the same for both models: it depends on the blocks only
  double spread[2], residual;
  int iterations[2];
  const char* models[2] = {"mass", "fractional"};
  for (int m = 0; m < 2; ++m) {
    const std::string prefix = std::string("test_frac_") + models[m] + "_";
    set_options(prefix, {{"ss_ksp_type", "preonly"}, {"ss_pc_type", "lu"}, {"contact_schur", models[m]}});
    solvers::ContactPreconditioner cp(PETSC_COMM_WORLD, prefix);
    cp.setup(sys.matrix, lambda->is, sys.multiplier_surface, exact.hp);
    EXPECT_EQ(cp.fractional_fit().fitted, m == 1);
    iterations[m] = gmres_iterations(sys, cp, &residual);
    EXPECT_LT(residual, 1e-9);
    if (m == 0) {
      Mat S = exact_contact_schur(sys, cp);
      exact_schur = to_dense(S);
      MatDestroy(&S);
    }
    spread[m] = spectral_spread(exact_schur, to_dense(cp.schur_approximation()), constrained);
    if (m == 1) {
      EXPECT_GT(cp.fractional_fit().beta, 0);
      EXPECT_EQ(cp.fractional_fit().rows, static_cast<int>(constrained.size()));
    }
  }
  std::printf("S~^-1 S_g spread on %zu constrained rows: mass %.2f, fractional %.2f; GMRES %d vs %d\n",
              constrained.size(), spread[0], spread[1], iterations[0], iterations[1]);
  EXPECT_LT(spread[1], spread[0]);
  EXPECT_LT(iterations[1], iterations[0]);
}

// The rational form of the fractional model (rational_fractional_schur.hpp) against its
// dense form on the same Newton system: the same fit (the Lanczos runs span the whole small
// spectrum, so mu_max agrees to round-off and beta to the Gauss quadrature's accuracy), and
// x = S~_rational^-1 b solves the dense S~ x = b to within a few times the rational
// approximation's tolerance, where the scaled mass, the rational form's starting point,
// misses by far more.
// On cattaneo-mindlin-2d (sticking, slipping and inactive nodes: S~ has D and slip-coupling
// rows beside G) and on hertz-cylinder-2d (a curved zone).
void expect_rational_form_solves_the_dense_model(StepSystem& step, const std::string& name) {
  const auto& sys = step.system();
  const auto* lambda = sys.field("lambda");
  ASSERT_NE(lambda, nullptr);
  ExactHierarchical exact(sys, "test_rat_hp_" + name + "_");
  const double tolerance = 1e-2;
  struct Model {
    const char *schur, *form;
  };
  const Model models[3] = {{"fractional", "dense"}, {"fractional", "rational"}, {"mass", "auto"}};
  std::vector<std::unique_ptr<solvers::ContactPreconditioner>> cps;
  for (const Model& m : models) {
    const std::string prefix = "test_rat_" + name + "_" + m.form + "_" + m.schur + "_";
    set_options(prefix, {{"ss_ksp_type", "preonly"},
                         {"ss_pc_type", "lu"},
                         {"contact_schur", m.schur},
                         {"contact_fractional_form", m.form},
                         {"contact_fractional_tol", "1e-2"}});
    cps.push_back(std::make_unique<solvers::ContactPreconditioner>(PETSC_COMM_WORLD, prefix));
    cps.back()->setup(sys.matrix, lambda->is, sys.multiplier_surface, exact.hp);
  }
  const solvers::FractionalFit &dense = cps[0]->fractional_fit(), &rational = cps[1]->fractional_fit();
  ASSERT_TRUE(dense.fitted);
  ASSERT_TRUE(rational.fitted);
  EXPECT_EQ(dense.rational_terms, 0);
  EXPECT_GT(rational.rational_terms, 0);
  EXPECT_LE(rational.rational_error, tolerance);
  EXPECT_EQ(rational.rows, dense.rows);
  EXPECT_NEAR(rational.mu_max, dense.mu_max, 1e-8 * dense.mu_max);
  EXPECT_NEAR(rational.beta, dense.beta, 1e-3 * dense.beta);

  Mat S_dense = cps[0]->schur_approximation();
  PetscVec b, work, x, residual;
  MatCreateVecs(S_dense, x.out(), b.out());
  VecDuplicate(b, work.out());
  VecDuplicate(b, residual.out());
  double worst[2] = {0, 0};  // rational, mass
  for (int trial = 0; trial < 4; ++trial) {
    PetscInt n, first;
    VecGetLocalSize(b, &n);
    VecGetOwnershipRange(b, &first, nullptr);
    for (PetscInt i = 0; i < n; ++i) VecSetValue(b, first + i, std::sin(1.0 + 0.37 * (trial + 1) * (first + i)), INSERT_VALUES);
    VecAssemblyBegin(b);
    VecAssemblyEnd(b);
    PetscReal b_norm, r_norm;
    VecNorm(b, NORM_2, &b_norm);
    for (int m = 0; m < 2; ++m) {
      VecCopy(b, work);  // solve_schur overwrites its right side
      cps[1 + m]->solve_schur(work, x);
      MatMult(S_dense, x, residual);
      VecAXPY(residual, -1.0, b);
      VecNorm(residual, NORM_2, &r_norm);
      worst[m] = std::max(worst[m], r_norm / b_norm);
    }
  }
  std::printf("%s: %d directions, %d rational terms (error %.2e); ||S_dense x - b|| / ||b||: rational %.2e, "
              "scaled mass %.2e\n",
              name.c_str(), rational.rows, rational.rational_terms, rational.rational_error, worst[0], worst[1]);
  EXPECT_LE(worst[0], 3 * tolerance);
  EXPECT_GE(worst[1], 10 * worst[0]);
}

TEST(ContactPreconditioner, RationalFractionalFormSolvesTheDenseModel) {
  StepSystem sticking("cattaneo-mindlin-2d");
  sticking.newton->solve_step(2);
  sticking.newton->solve_step(3);
  expect_rational_form_solves_the_dense_model(sticking, "cattaneo");
  StepSystem curved("hertz-cylinder-2d");
  expect_rational_form_solves_the_dense_model(curved, "hertz");
}

// On the paper's block with strips (level 0) the contact zone's 2 454 node rows exceed the
// dense form's 1 500: schur-amg uses the rational form by default, and the first load step
// takes fewer Krylov iterations with it than with the scaled mass (32) it replaces.
TEST(ContactPreconditioner, BlockWithStripsUsesTheRationalFractionalForm) {
  auto run = [](bool mass) {
    if (mass) PetscOptionsSetValue(nullptr, "-schur_amg_contact_schur", "mass");
    auto scene = harness::open_scene("block-strips", 0);
    auto solver = solvers::create_solver("schur-amg", PETSC_COMM_WORLD);
    nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, scene->problem, scene->newton, *solver);
    const nonlinear::StepResult result = newton.solve_step(1);
    PetscOptionsClearValue(nullptr, "-schur_amg_contact_schur");
    EXPECT_TRUE(result.converged());
    int krylov = 0, rational = 0;
    for (const auto& it : result.iterations) {
      krylov += it.linear.iterations;
      const auto nodes = it.linear.extra.find("contact_fractional_nodes");
      if (nodes != it.linear.extra.end() && nodes->second > 0) ++rational;
    }
    return std::pair{krylov, rational};
  };
  const auto [rational_krylov, rational_solves] = run(false);
  const auto [mass_krylov, mass_rational_solves] = run(true);
  std::printf("block-strips level 0, step 1: %d Krylov iterations with the rational form, %d with the mass\n",
              rational_krylov, mass_krylov);
  EXPECT_GT(rational_solves, 0);
  EXPECT_EQ(mass_rational_solves, 0);
  EXPECT_LT(rational_krylov, mass_krylov);
}

// [[0 1 0] [1 0 0] [0 0 4]]: nonsingular, and its 2x2 block has zero diagonals in either
// order, like a constrained node's normal row in S~ (no diagonal entry of its own in D).
PetscMat zero_diagonal_matrix() {
  PetscMat A;
  STICTION_PETSC(MatCreateSeqAIJ(PETSC_COMM_SELF, 3, 3, 2, nullptr, A.out()));
  for (PetscInt i = 0; i < 2; ++i) STICTION_PETSC(MatSetValue(A, i, i, 0.0, INSERT_VALUES));
  STICTION_PETSC(MatSetValue(A, 0, 1, 1.0, INSERT_VALUES));
  STICTION_PETSC(MatSetValue(A, 1, 0, 1.0, INSERT_VALUES));
  STICTION_PETSC(MatSetValue(A, 2, 2, 4.0, INSERT_VALUES));
  STICTION_PETSC(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  return A;
}

// The largest error of the solve of A x = A (1, 2, 3) by a preonly KSP with this prefix.
double direct_solve_error(const std::string& prefix, Mat A) {
  PetscKSP ksp;
  STICTION_PETSC(KSPCreate(PETSC_COMM_SELF, ksp.out()));
  STICTION_PETSC(KSPSetOptionsPrefix(ksp, prefix.c_str()));
  STICTION_PETSC(KSPSetOperators(ksp, A, A));
  STICTION_PETSC(KSPSetFromOptions(ksp));
  PetscVec x, b, exact;
  STICTION_PETSC(MatCreateVecs(A, x.out(), b.out()));
  STICTION_PETSC(VecDuplicate(x, exact.out()));
  for (PetscInt i = 0; i < 3; ++i) STICTION_PETSC(VecSetValue(exact, i, i + 1.0, INSERT_VALUES));
  STICTION_PETSC(VecAssemblyBegin(exact));
  STICTION_PETSC(VecAssemblyEnd(exact));
  STICTION_PETSC(MatMult(A, exact, b));
  STICTION_PETSC(KSPSolve(ksp, b, x));
  STICTION_PETSC(VecAXPY(x, -1.0, exact));
  PetscReal error;
  STICTION_PETSC(VecNorm(x, NORM_INFINITY, &error));
  return error;
}

// The Schur backends' contact level (the ss_ solver of S~) factors with pivoting: PETSc's
// own LU, which does not pivot, fails on a matrix with zero diagonal entries.
TEST(ContactPreconditioner, SchurBackendsFactorTheContactLevelWithPivoting) {
  const PetscMat A = zero_diagonal_matrix();
  set_options("test_pivot_", {{"ksp_type", "preonly"}, {"pc_type", "lu"}, {"pc_factor_mat_solver_type", "petsc"}});
  ASSERT_FALSE(std::isfinite(direct_solve_error("test_pivot_", A)));  // the case needs pivoting
  for (const char* backend : {"schur-amg", "schur-lu", "schur-gamg"}) {
    const auto solver = solvers::create_solver(backend, PETSC_COMM_WORLD);  // its options into the database
    EXPECT_LT(direct_solve_error(solvers::options_prefix(backend) + "ss_", A), 1e-14) << backend;
  }
}

}  // namespace
}  // namespace stiction::test
