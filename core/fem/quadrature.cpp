#include "fem/quadrature.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/error.hpp"

namespace stiction::fem {

namespace {

// Gauss-Legendre nodes and weights on [0, 1] by Newton's method on P_n.
void gauss_legendre01(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1, p1 = z;
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = 0.5 * (1 - z);
    w[i] = 1.0 / ((1 - z * z) * dp * dp);  // 2/((1-z^2) P'^2) scaled by 1/2 to [0,1]
  }
}

QuadratureRule collapsed_rule(int dim, int degree) {
  // The collapsed map adds (dim - 1) to the degree in the first direction: n points give
  // exactness 2n - 1, so n = ceil((degree + dim) / 2) covers every direction.
  const int n = (degree + dim + 1) / 2;
  std::vector<double> x, w;
  gauss_legendre01(std::max(n, 1), x, w);
  QuadratureRule r{dim, degree, {}, {}};
  const int m = static_cast<int>(x.size());
  if (dim == 1) {
    r.points = x;
    r.weights = w;
  } else if (dim == 2) {
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) {
        const double s = x[i], t = x[j];
        r.points.insert(r.points.end(), {s, t * (1 - s)});
        r.weights.push_back(w[i] * w[j] * (1 - s));
      }
  } else {
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        for (int k = 0; k < m; ++k) {
          const double s = x[i], t = x[j], u = x[k];
          r.points.insert(r.points.end(), {s, t * (1 - s), u * (1 - s) * (1 - t)});
          r.weights.push_back(w[i] * w[j] * w[k] * (1 - s) * (1 - s) * (1 - t));
        }
  }
  return r;
}

}  // namespace

QuadratureRule simplex_quadrature(int dim, int degree) {
  if (dim < 1 || dim > 3) throw Error(fmt::format("quadrature: dimension {}", dim), ErrorKind::Internal);
  if (degree <= 1) {  // centroid
    QuadratureRule r{dim, 1, std::vector<double>(dim, 1.0 / (dim + 1)), {dim == 1 ? 1.0 : dim == 2 ? 0.5 : 1.0 / 6}};
    return r;
  }
  if (degree == 2 && dim == 2) {
    const double a = 1.0 / 6, b = 2.0 / 3;
    return {2, 2, {a, a, b, a, a, b}, {1.0 / 6, 1.0 / 6, 1.0 / 6}};
  }
  if (degree == 2 && dim == 3) {
    const double a = 0.1381966011250105, b = 0.5854101966249685;  // (5 -+ sqrt 5)/20
    return {3, 2, {a, a, a, b, a, a, a, b, a, a, a, b}, {1.0 / 24, 1.0 / 24, 1.0 / 24, 1.0 / 24}};
  }
  return collapsed_rule(dim, degree);
}

}  // namespace stiction::fem
