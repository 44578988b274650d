#pragma once
// Zolotarev's best uniform relative approximation of x^-1/2 on an interval, in partial
// fractions: the fewest linear solves for a given accuracy when x is the spectrum of an SPD
// pencil (each term is one shifted solve).
//
// On t = x / x_low in [1, b], b = x_high / x_low, with k' = sqrt(1 - 1/b), K' = K(k') and
// c_l = sn^2(l K' / (2n + 1); k') / cn^2(l K' / (2n + 1); k'), l = 1..2n,
//
//   t^-1/2 ~ d prod_{l=1..n} (t + c_2l) / (t + c_2l-1)
//          = d (1 + sum_l b_l / (t + c_2l-1)),
//   b_l = prod_k (c_2k - c_2l-1) / prod_{k != l} (c_2k-1 - c_2l-1) > 0 (the c interlace),
//
// (Zolotarev 1877; in this form e.g. Chiu, Hsieh, Huang and Huang, Phys. Rev. D 66 (2002) 114502).
// The scale d is set here from the extremes of sqrt(t) prod(...) on a fine grid, which makes
// the relative error equioscillate; the error reported is the one measured on that grid.
// The degree n is the smallest whose error is at most the tolerance.
#include <vector>

namespace stiction::solvers {

struct InverseSquareRootApproximation {
  // x^-1/2 ~ constant + sum_k weight[k] / (x + shift[k]); weights and shifts positive
  double constant = 0;
  std::vector<double> weight, shift;
  double error = 0;  // max |approximation * sqrt(x) - 1| on the grid
};

// Over [x_low, x_high] (0 < x_low <= x_high), with relative error at most `tolerance` when
// `max_terms` terms suffice (otherwise the best of max_terms, its error reported).
InverseSquareRootApproximation zolotarev_inverse_square_root(double x_low, double x_high, double tolerance,
                                                             int max_terms = 24);

}  // namespace stiction::solvers
