#pragma once
// The fractional model of the contact Schur complement (fractional_schur.hpp) for contact
// zones too large for its dense eigendecomposition: its inverse applied through sparse
// factorisations of the surface, a rational approximation.
//
// On the constrained directions (the columns of T; reduced mass M, reduced stiffness K) the
// model is G = C M X^-1/2 with X = M^-1 (K + beta M) and C = s_high sqrt(mu_max + beta),
// the dense model's g(mu) = s_high sqrt((mu_max + beta) / (mu + beta)). So
//
//   G^-1 = C^-1 X^1/2 M^-1 = C^-1 M^-1 (K + beta M) X^-1/2 M^-1,
//   X^-1/2 M^-1 ~ w_0 M^-1 + sum_k w_k (K + sigma_k M)^-1,   sigma_k = beta + tau_k,
//
// from Zolotarev's best relative approximation x^-1/2 ~ w_0 + sum_k w_k / (x + tau_k) over
// the spectrum of X (zolotarev.hpp), of the smallest degree whose error is below
// `tolerance` (4 to 6 terms for 1e-2 on spectra spanning 1e4 to 1e8). Each K + sigma_k M is
// a sparse SPD surface matrix, factored once per set-up.
//
// S~ = S0 + T G T^T, where S0 (D and the slip coupling) has no constrained row (T^T S0 = 0:
// a constrained direction's equation involves the displacement only). Then S~ x = b splits:
// T^T x = G^-1 T^T b and S0 x = (I - T T^T) b, which the scaled-mass approximation
// S_m = S0 + s T M T^T solves together:
//
//   x = S_m^-1 (b - T T^T b + s T M G^-1 T^T b),
//
// so the model needs the mass model's factorisation and one right-side correction.
//
// The two constants come from the spectrum of M^-1 K as in the dense model: mu_max is the
// largest Ritz value of Lanczos runs, and beta matches the model's Rayleigh quotient on the
// smooth probe to s_smooth through the Gauss quadrature of a Lanczos run started from the
// probe. One process only: on several, the caller keeps the dense model or the scaled mass.
#include <memory>

#include "common/petsc.hpp"
#include "fractional_schur.hpp"

namespace stiction::solvers {

class RationalFractionalCorrection {
public:
  RationalFractionalCorrection();
  ~RationalFractionalCorrection();
  // mass = Pi M Pi and stiffness = Pi K Pi on the multiplier numbering, dim multiplier
  // components per node; D and slip_coupling the rest of S~ (checked to have no constrained
  // row); s the scaled mass's factor in S_m. False, with fit.fitted false, when the
  // estimates do not bracket (s_smooth <= s_high), the zone has fewer than 2 directions or
  // D or the slip coupling has a constrained row: the caller keeps the scaled mass.
  bool setup(Mat mass, Mat stiffness, Mat D, Mat slip_coupling, int dim, double s, double s_high, double s_smooth,
             double tolerance, FractionalFit& fit);
  // out = b - T T^T b + s T M G^-1 T^T b (out may be b).
  void correct(Vec b, Vec out) const;

  struct Factors;  // the directions, the reduced surface matrices and their factorisations

private:
  std::unique_ptr<Factors> factors_;
};

}  // namespace stiction::solvers
