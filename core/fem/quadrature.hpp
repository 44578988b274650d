#pragma once
// Quadrature on the reference simplex {x_i >= 0, sum x_i <= 1} of dimension 1, 2 or 3.
#include <cstddef>
#include <vector>

namespace stiction::fem {

struct QuadratureRule {
  int dim = 0;
  int degree = 0;               // exact for polynomials up to this total degree
  std::vector<double> points;   // n x dim
  std::vector<double> weights;  // sum = reference measure 1/dim!
  int size() const { return static_cast<int>(weights.size()); }
  const double* point(int q) const { return points.data() + static_cast<size_t>(q) * dim; }
};

// Symmetric rules with positive weights up to degree 2 (the assembly rules: P2 stiffness
// of linear elasticity is degree 2); for higher degrees a collapsed (Duffy) Gauss-Legendre
// product rule, exact to the requested degree (used for error norms and loads).
QuadratureRule simplex_quadrature(int dim, int degree);

}  // namespace stiction::fem
