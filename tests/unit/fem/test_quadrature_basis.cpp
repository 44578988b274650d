// Quadrature exactness on monomials and the shape-function identities.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fem/basis.hpp"
#include "fem/quadrature.hpp"
#include "mesh/mesh.hpp"

namespace stiction::fem {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// int over the reference simplex of x^a y^b z^c = a! b! c! / (a + b + c + dim)!
TEST(Quadrature, ExactOnMonomials) {
  for (int dim = 1; dim <= 3; ++dim)
    for (int degree = 1; degree <= 8; ++degree) {
      const QuadratureRule r = simplex_quadrature(dim, degree);
      for (int a = 0; a <= degree; ++a)
        for (int b = 0; b <= (dim > 1 ? degree - a : 0); ++b)
          for (int c = 0; c <= (dim > 2 ? degree - a - b : 0); ++c) {
            double sum = 0;
            for (int q = 0; q < r.size(); ++q) {
              const double* x = r.point(q);
              sum += r.weights[q] * std::pow(x[0], a) * (dim > 1 ? std::pow(x[1], b) : 1.0) *
                     (dim > 2 ? std::pow(x[2], c) : 1.0);
            }
            const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + dim);
            EXPECT_NEAR(sum, exact, 1e-14 + 1e-12 * exact) << "dim " << dim << " degree " << degree << " x^" << a
                                                           << " y^" << b << " z^" << c;
          }
    }
}

using DimAndBasis = std::tuple<int, BasisKind>;
std::string name_of(const ::testing::TestParamInfo<DimAndBasis>& info) {
  std::string basis = to_string(std::get<1>(info.param));
  for (char& c : basis)
    if (c == '-') c = '_';
  return std::to_string(std::get<0>(info.param)) + "D_" + basis;
}

class ShapeFunctions : public ::testing::TestWithParam<DimAndBasis> {};
class EdgeFunctions : public ::testing::TestWithParam<DimAndBasis> {};

TEST_P(ShapeFunctions, PartitionOfUnityAndGradients) {
  const auto [d, kind] = GetParam();
  const int n = n_shape_functions(d, kind);
  std::vector<double> N(n), dN(n * d), Np(n), Nm(n), tmp(n * d);
  const double xi[3] = {0.21, 0.17, 0.33};
  eval_shape(d, kind, xi, N.data(), dN.data());
  // The constant 1: all functions (P1, nodal P2) or the vertex functions (hierarchical).
  double sum = 0;
  for (int a = 0; a < (kind == BasisKind::P2Hierarchical ? d + 1 : n); ++a) sum += N[a];
  EXPECT_NEAR(sum, 1.0, 1e-14);
  const double h = 1e-6;
  for (int j = 0; j < d; ++j) {
    double xp[3] = {xi[0], xi[1], xi[2]}, xm[3] = {xi[0], xi[1], xi[2]};
    xp[j] += h;
    xm[j] -= h;
    eval_shape(d, kind, xp, Np.data(), tmp.data());
    eval_shape(d, kind, xm, Nm.data(), tmp.data());
    for (int a = 0; a < n; ++a) EXPECT_NEAR(dN[a * d + j], (Np[a] - Nm[a]) / (2 * h), 1e-8);
  }
}

TEST_P(EdgeFunctions, AreOneAtTheirMidpoint) {
  const auto [d, kind] = GetParam();
  const int n = n_shape_functions(d, kind);
  std::vector<double> N(n), dN(n * d);
  for (int e = 0; e < mesh::n_simplex_edges(d); ++e) {
    const auto [a, b] = mesh::simplex_edge(d, e);
    double xi[3] = {0, 0, 0};  // vertex v of the reference simplex: 0 or unit vector e_{v-1}
    for (int v : {a, b})
      if (v > 0) xi[v - 1] += 0.5;
    eval_shape(d, kind, xi, N.data(), dN.data());
    EXPECT_NEAR(N[d + 1 + e], 1.0, 1e-14);
    // Nodal P2 is Lagrange: every other function vanishes at the midpoint.
    if (kind == BasisKind::P2Nodal)
      for (int k = 0; k < n; ++k)
        if (k != d + 1 + e) {
          EXPECT_NEAR(N[k], 0.0, 1e-14);
        }
  }
}

INSTANTIATE_TEST_SUITE_P(All, ShapeFunctions,
                         ::testing::Combine(::testing::Values(1, 2, 3),
                                            ::testing::Values(BasisKind::P1, BasisKind::P2Nodal,
                                                              BasisKind::P2Hierarchical)),
                         name_of);
INSTANTIATE_TEST_SUITE_P(Quadratic, EdgeFunctions,
                         ::testing::Combine(::testing::Values(1, 2, 3),
                                            ::testing::Values(BasisKind::P2Nodal, BasisKind::P2Hierarchical)),
                         name_of);

}  // namespace
}  // namespace stiction::fem
