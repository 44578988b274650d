#include "zolotarev.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

namespace stiction::solvers {

namespace {

// The degree-n approximation on [1, b], unscaled (d = 1), and its extremes on the grid.
struct Unscaled {
  std::vector<double> weight, shift;
  double low = 0, high = 0;  // min and max of sqrt(t) (1 + sum_l b_l / (t + c_2l-1))
};

Unscaled zolotarev_terms(double b, int n) {
  const double k_prime = std::sqrt(1.0 - 1.0 / b);
  const double K_prime = boost::math::ellint_1(k_prime);
  std::vector<double> c(2 * n + 1);
  for (int l = 1; l <= 2 * n; ++l) {
    double cn = 0, dn = 0;
    const double sn = boost::math::jacobi_elliptic(k_prime, l * K_prime / (2 * n + 1), &cn, &dn);
    c[l] = sn * sn / (cn * cn);  // cn from the elliptic functions, not sqrt(1 - sn^2): no cancellation
  }
  Unscaled u;
  for (int l = 1; l <= n; ++l) {
    double numerator = 1, denominator = 1;
    for (int k = 1; k <= n; ++k) {
      numerator *= c[2 * k] - c[2 * l - 1];
      if (k != l) denominator *= c[2 * k - 1] - c[2 * l - 1];
    }
    u.weight.push_back(numerator / denominator);
    u.shift.push_back(c[2 * l - 1]);
  }
  constexpr int kGrid = 2000;
  u.low = INFINITY, u.high = 0;
  for (int i = 0; i <= kGrid; ++i) {
    const double t = std::pow(b, static_cast<double>(i) / kGrid);
    double p = 1;
    for (int l = 0; l < n; ++l) p += u.weight[l] / (t + u.shift[l]);
    p *= std::sqrt(t);
    u.low = std::min(u.low, p), u.high = std::max(u.high, p);
  }
  return u;
}

}  // namespace

InverseSquareRootApproximation zolotarev_inverse_square_root(double x_low, double x_high, double tolerance,
                                                             int max_terms) {
  if (!(x_low > 0) || !(x_high >= x_low) || !std::isfinite(x_high))
    throw std::invalid_argument("zolotarev_inverse_square_root: needs 0 < x_low <= x_high < inf");
  const double b = x_high / x_low;
  Unscaled u;
  int n = 1;
  for (; n <= max_terms; ++n) {
    u = zolotarev_terms(b, n);
    if ((u.high - u.low) / (u.high + u.low) <= tolerance) break;
  }
  // t = x / x_low: x^-1/2 = x_low^-1/2 d (1 + sum_l b_l x_low / (x + x_low c_2l-1)), d = 2 / (low + high)
  const double d = 2.0 / (u.low + u.high), root = std::sqrt(x_low);
  InverseSquareRootApproximation a;
  a.constant = d / root;
  for (size_t l = 0; l < u.weight.size(); ++l) {
    a.weight.push_back(d * u.weight[l] * root);
    a.shift.push_back(x_low * u.shift[l]);
  }
  a.error = (u.high - u.low) / (u.high + u.low);
  return a;
}

}  // namespace stiction::solvers
