// Convergence of P1 and P2 (hierarchical) on a manufactured linear-elasticity solution, the
// equivalence of the hierarchical and nodal P2 bases, and A_ll = P1 stiffness.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem/elasticity_assembly.hpp"
#include "materials/material.hpp"
#include "support/manufactured.hpp"

namespace stiction {
namespace {

using fem::BasisKind;

struct RateCase {
  int dim, n, coarse_level;
  BasisKind kind;
  double l2_rate, h1_rate;
};

// Rates between levels coarse_level and coarse_level + 1 (mesh size halves).
class ConvergenceRate : public ::testing::TestWithParam<RateCase> {};

TEST_P(ConvergenceRate, MatchesTheory) {
  const RateCase c = GetParam();
  const auto coarse = test::solve_manufactured(c.dim, c.n, c.coarse_level, c.kind);
  const auto fine = test::solve_manufactured(c.dim, c.n, c.coarse_level + 1, c.kind);
  const double l2 = std::log2(coarse.errors.l2 / fine.errors.l2);
  const double h1 = std::log2(coarse.errors.h1_seminorm / fine.errors.h1_seminorm);
  std::printf("measured rates: L2 %.3f, H1 %.3f (levels %d -> %d)\n", l2, h1, c.coarse_level, c.coarse_level + 1);
  EXPECT_NEAR(l2, c.l2_rate, 0.2) << "L2 errors " << coarse.errors.l2 << " -> " << fine.errors.l2;
  EXPECT_NEAR(h1, c.h1_rate, 0.2) << "H1 errors " << coarse.errors.h1_seminorm << " -> " << fine.errors.h1_seminorm;
}

INSTANTIATE_TEST_SUITE_P(Elasticity, ConvergenceRate,
                         ::testing::Values(RateCase{2, 4, 2, BasisKind::P1, 2, 1},
                                           RateCase{2, 4, 1, BasisKind::P2Hierarchical, 3, 2},
                                           RateCase{3, 2, 2, BasisKind::P1, 2, 1},
                                           RateCase{3, 2, 1, BasisKind::P2Hierarchical, 3, 2}),
                         [](const auto& info) {
                           return std::to_string(info.param.dim) + "D_" +
                                  (info.param.kind == BasisKind::P1 ? "P1" : "P2");
                         });

// The hierarchical and nodal bases span the same space: identical discrete solutions.
class BasisEquivalence : public ::testing::TestWithParam<int> {};

TEST_P(BasisEquivalence, SameDiscreteSolution) {
  const int dim = GetParam();
  const auto h = test::solve_manufactured(dim, 2, 1, BasisKind::P2Hierarchical);
  const auto n = test::solve_manufactured(dim, 2, 1, BasisKind::P2Nodal);
  const auto vh = h.space->nodal_values(h.u), vn = n.space->nodal_values(n.u);
  ASSERT_EQ(vh.size(), vn.size());
  double diff = 0, scale = 0;
  for (size_t i = 0; i < vh.size(); ++i) {
    diff = std::max(diff, std::abs(vh[i] - vn[i]));
    scale = std::max(scale, std::abs(vn[i]));
  }
  EXPECT_LT(diff, 1e-10 * scale);
  EXPECT_GT(scale, 0.1);  // a non-trivial solution
}

INSTANTIATE_TEST_SUITE_P(Dimensions, BasisEquivalence, ::testing::Values(2, 3));

// A_ll (vertex block of the hierarchical P2 tangent) is the P1 tangent, also at a
// deformed state: for a state linear in X the edge coefficients vanish and both spaces
// hold the same deformation.
class LinearBlockIsP1 : public ::testing::TestWithParam<int> {};

TEST_P(LinearBlockIsP1, ToRoundOff) {
  const int dim = GetParam();
  const mesh::Mesh m = mesh::refine(mesh::structured_box(dim, {1, 1.5, 0.8}, {2, 2, 2}), 1);
  materials::NeoHookean law(10.0, 0.3);
  const std::vector<const materials::Material*> mats(m.n_cells(), &law);
  const auto deform = [dim](const double* X, double* u) {
    for (int i = 0; i < dim; ++i) {
      u[i] = 0;
      for (int j = 0; j < dim; ++j) u[i] += 0.05 * (i + 1) * (j == i ? 1.0 : 0.3 * (j + 1)) * X[j];
    }
  };
  auto tangent = [&](BasisKind kind, std::vector<double>& residual) {
    fem::FieldSpace space(m, kind);
    std::vector<double> u;
    space.interpolate(deform, u);
    residual.assign(space.n_dofs(), 0.0);
    fem::StiffnessMatrix K(PETSC_COMM_WORLD, space);
    K.begin_assembly();
    fem::assemble_internal(space, mats, u, residual, &K);
    K.end_assembly();
    Mat A = K.mat();
    PetscObjectReference(reinterpret_cast<PetscObject>(A));
    return A;
  };
  std::vector<double> r1, r2;
  Mat P1 = tangent(BasisKind::P1, r1);
  Mat P2 = tangent(BasisKind::P2Hierarchical, r2);
  IS linear;
  ISCreateStride(PETSC_COMM_WORLD, m.n_vertices() * dim, 0, 1, &linear);
  Mat All;
  MatCreateSubMatrix(P2, linear, linear, MAT_INITIAL_MATRIX, &All);
  PetscReal norm_p1, norm_diff;
  MatNorm(P1, NORM_FROBENIUS, &norm_p1);
  MatAXPY(All, -1.0, P1, DIFFERENT_NONZERO_PATTERN);
  MatNorm(All, NORM_FROBENIUS, &norm_diff);
  EXPECT_LT(norm_diff, 1e-13 * norm_p1);
  for (int i = 0; i < m.n_vertices() * dim; ++i) EXPECT_NEAR(r2[i], r1[i], 1e-13 * norm_p1);
  MatDestroy(&All);
  MatDestroy(&P1);
  MatDestroy(&P2);
  ISDestroy(&linear);
}

INSTANTIATE_TEST_SUITE_P(Dimensions, LinearBlockIsP1, ::testing::Values(2, 3));

}  // namespace
}  // namespace stiction
