#include "fem/error_norms.hpp"

#include <Eigen/Dense>

#include <cmath>

#include "fem/quadrature.hpp"

namespace stiction::fem {

ErrorNorms compute_errors(const FieldSpace& space, const std::vector<double>& u, const VectorField& exact,
                          const VectorGradient& exact_gradient, int degree) {
  const int d = space.dim(), nb = space.nodes_per_cell();
  const QuadratureRule rule = simplex_quadrature(d, degree);
  std::vector<double> N(nb), dN(nb * d);
  std::vector<int> nodes(nb);
  double l2 = 0, h1 = 0, X[3], ue[3], ge[9];
  for (int c = 0; c < space.mesh().n_cells(); ++c) {
    space.cell_nodes(c, nodes.data());
    const int* v = space.mesh().cell(c);
    const double* X0 = space.mesh().vertex(v[0]);
    Eigen::MatrixXd J(d, d);
    for (int j = 0; j < d; ++j)
      for (int i = 0; i < d; ++i) J(i, j) = space.mesh().vertex(v[j + 1])[i] - X0[i];
    const Eigen::MatrixXd inv = J.inverse();
    const double det = std::abs(J.determinant());
    for (int q = 0; q < rule.size(); ++q) {
      const double* xi = rule.point(q);
      eval_shape(d, space.kind(), xi, N.data(), dN.data());
      for (int i = 0; i < d; ++i) {
        X[i] = X0[i];
        for (int j = 0; j < d; ++j) X[i] += J(i, j) * xi[j];
      }
      exact(X, ue);
      exact_gradient(X, ge);
      for (int i = 0; i < d; ++i) {
        double uh = 0;
        double gh[3] = {0, 0, 0};
        for (int a = 0; a < nb; ++a) {
          const double coef = u[static_cast<size_t>(nodes[a]) * d + i];
          uh += coef * N[a];
          for (int Jx = 0; Jx < d; ++Jx)
            for (int j = 0; j < d; ++j) gh[Jx] += coef * dN[a * d + j] * inv(j, Jx);
        }
        l2 += rule.weights[q] * det * std::pow(ue[i] - uh, 2);
        for (int Jx = 0; Jx < d; ++Jx) h1 += rule.weights[q] * det * std::pow(ge[i * d + Jx] - gh[Jx], 2);
      }
    }
  }
  return {std::sqrt(l2), std::sqrt(h1)};
}

}  // namespace stiction::fem
