#pragma once
// Errors of a discrete displacement against an exact one, for convergence studies:
// ||u - u_h||_L2 and |u - u_h|_H1, by quadrature of the given degree on every cell.
#include <functional>
#include <vector>

#include "fem/app_view.hpp"
#include "fem/field_space.hpp"

namespace stiction::fem {

// grad(X, out): out[i * dim + J] = d u_i / d X_J.
using VectorGradient = std::function<void(const double* X, double* out)>;

struct ErrorNorms {
  double l2 = 0;
  double h1_seminorm = 0;
};

ErrorNorms compute_errors(const FieldSpace& space, StateView u, const VectorField& exact,
                          const VectorGradient& exact_gradient, int quadrature_degree = 6);

}  // namespace stiction::fem
