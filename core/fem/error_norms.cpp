#include "fem/error_norms.hpp"

#include <Eigen/Dense>

#include <cmath>

#include "fem/cell_geometry.hpp"
#include "fem/quadrature.hpp"

namespace stiction::fem {

namespace {

template <int D>
ErrorNorms errors_in(const FieldSpace& space, StateView u, const VectorField& exact,
                     const VectorGradient& exact_gradient, int degree) {
  const int nb = space.nodes_per_cell();
  const QuadratureRule rule = simplex_quadrature(D, degree);
  std::vector<double> N(nb), dN(nb * D);
  std::vector<int> nodes(nb);
  double l2 = 0, h1 = 0, X[3], ue[3], ge[9];
  for (int c = 0; c < space.mesh().n_cells(); ++c) {
    space.cell_nodes(c, nodes.data());
    const int* v = space.mesh().cell(c);
    for (int q = 0; q < rule.size(); ++q) {
      const double* xi = rule.point(q);
      eval_shape(D, space.kind(), xi, N.data(), dN.data());
      const CellMap<D> geo = cell_map<D>(simplex_jacobian<D, D>(space, v, nodes.data(), nb, dN.data()));
      const double det = std::abs(geo.det);
      simplex_position<D, D>(space, v, nodes.data(), nb, xi, N.data(), X);
      exact(X, ue);
      exact_gradient(X, ge);
      for (int i = 0; i < D; ++i) {
        double uh = 0;
        double gh[3] = {0, 0, 0};
        for (int a = 0; a < nb; ++a) {
          const double coef = u[static_cast<size_t>(nodes[a]) * D + i];
          uh += coef * N[a];
          for (int Jx = 0; Jx < D; ++Jx)
            for (int j = 0; j < D; ++j) gh[Jx] += coef * dN[a * D + j] * geo.inv(j, Jx);
        }
        l2 += rule.weights[q] * det * std::pow(ue[i] - uh, 2);
        for (int Jx = 0; Jx < D; ++Jx) h1 += rule.weights[q] * det * std::pow(ge[i * D + Jx] - gh[Jx], 2);
      }
    }
  }
  return {std::sqrt(l2), std::sqrt(h1)};
}

}  // namespace

ErrorNorms compute_errors(const FieldSpace& space, StateView u, const VectorField& exact,
                          const VectorGradient& exact_gradient, int degree) {
  return space.dim() == 2 ? errors_in<2>(space, u, exact, exact_gradient, degree)
                          : errors_in<3>(space, u, exact, exact_gradient, degree);
}

}  // namespace stiction::fem
