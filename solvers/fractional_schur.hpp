#pragma once
// A fractional model of the contact Schur complement on the constrained directions, an
// alternative to the paper's scaled mass (32) (-<prefix>contact_schur fractional).
//
// Why: on the constrained directions S_g = B A^-1 B^T is the body's compliance seen through
// the multiplier: the inverse of a Steklov-Poincare operator, of order -1 (a half-space
// answers a surface load of wave number k with a displacement ~ 1 / (E* k)). A scaled mass
// s M is of order 0: it can be right at one wave number only, so the spectrum of S~^-1 S_g
// widens like 1 / h under refinement. The model
//
//   G = M V diag(g(mu)) V^T M,   K V = M V diag(mu),  V^T M V = I,
//   g(mu) = s_high sqrt((mu_max + beta) / (mu + beta))
//
// (M = Pi M_lambda Pi, K = Pi K_surface Pi on the constrained rows) has the order -1
// (g ~ 1 / k for mu ~ k^2 >> beta) and reduces to s M when g is constant. Its two
// parameters come from the two compliance estimates the preconditioner already measures:
// g(mu_max) = s_high, the element-end estimate (the most oscillating load is answered
// almost locally, by diag(A)^-1); beta such that the model's Rayleigh quotient on the
// smooth probe w equals s_smooth, the body-end estimate through the inner preconditioner.
// beta ~ 1 / L^2 sets the length beyond which the finite body stops looking like a
// half-space. No material constant enters: the calibration reads the current tangent.
//
// Cost: a dense generalised eigenproblem on the constrained directions (every rank holds
// them; they live on the contact zone only): ~n_c^3 flops once per Newton iteration, a few
// ms for the n_c <= 300 of the built-in scenes. Above max_rows no model is built and the
// caller uses the model's rational form (rational_fractional_schur.hpp) on one process, and
// the scaled mass on several.

#include <Eigen/Dense>

#include "common/petsc.hpp"

namespace stiction::solvers {

struct FractionalFit {
  bool fitted = false;  // false: s_smooth <= s_high, or too many rows; G was not built
  double beta = 0, mu_max = 0;
  int rows = 0;  // constrained directions (the model's size)
  // The rational form (rational_fractional_schur.hpp): its terms (one shifted factorisation
  // each) and the largest relative error of its X^-1/2 over the spectrum; 0 for the dense form.
  int rational_terms = 0;
  double rational_error = 0;
};

// One node's constrained directions, as columns: the eigenvectors of its diagonal block of
// Pi M Pi whose eigenvalues exceed 1e-10 of the largest (all of R^dim at a sticking node,
// the normal at a slipping one, none at an inactive one).
Eigen::MatrixXd node_constrained_directions(const Eigen::MatrixXd& block);

// The model's beta: the Rayleigh quotient of G on the smooth probe, sum_k weights_k g(mu_k),
// equals s_smooth (weights: the probe's M-normalised spectral weights on the eigenvalues or
// Ritz values mu, summing to 1), found by bisection on log beta (an end of the bracket
// [mu_max 1e-12, mu_max 1e12] when s_smooth lies outside the quotient's range).
double fit_fractional_beta(const Eigen::VectorXd& mu, const Eigen::VectorXd& weights, double mu_max, double s_high,
                           double s_smooth);

// G on the multiplier numbering of `mass` (zero outside the constrained rows), or an empty
// handle when the fit fails (see FractionalFit).
// dim: multiplier components per node (the rows come in node blocks).
PetscMat fractional_compliance(Mat mass, Mat stiffness, int dim, double s_high, double s_smooth, int max_rows,
                               FractionalFit& fit);

}  // namespace stiction::solvers
