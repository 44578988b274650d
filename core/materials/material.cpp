#include "materials/material.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/error.hpp"

namespace stiction::materials {

void lame_parameters(double E, double nu, double& lambda, double& mu) {
  if (!(E > 0)) throw Error(fmt::format("Young's modulus E = {} must be positive", E));
  if (!(nu > -1 && nu < 0.5))
    throw Error(fmt::format("Poisson's ratio nu = {} must lie in (-1, 0.5)", nu));
  mu = E / (2 * (1 + nu));
  lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
}

LinearElastic::LinearElastic(double E, double nu) : E_(E), nu_(nu) { lame_parameters(E, nu, lambda_, mu_); }

std::string LinearElastic::describe() const { return fmt::format("linear elastic (E = {:g}, nu = {:g})", E_, nu_); }

double LinearElastic::energy(const Mat3& F) const {
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  return 0.5 * lambda_ * eps.trace() * eps.trace() + mu_ * (eps.array() * eps.array()).sum();
}

Mat3 LinearElastic::first_piola(const Mat3& F) const {
  const Mat3 eps = 0.5 * (F + F.transpose()) - Mat3::Identity();
  return lambda_ * eps.trace() * Mat3::Identity() + 2 * mu_ * eps;
}

void LinearElastic::first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const {
  P = first_piola(F);
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L)
          A[tangent_index(i, J, k, L)] =
              lambda_ * (i == J) * (k == L) + mu_ * ((i == k) * (J == L) + (i == L) * (J == k));
}

NeoHookean::NeoHookean(double E, double nu) : E_(E), nu_(nu) { lame_parameters(E, nu, lambda_, mu_); }

std::string NeoHookean::describe() const {
  return fmt::format("compressible Neo-Hookean, Wriggers' form (E = {:g}, nu = {:g}; mu = {:g}, Lambda = {:g})",
                     E_, nu_, mu_, lambda_);
}

double NeoHookean::energy(const Mat3& F) const {
  const double J = F.determinant();
  const double I1 = (F.transpose() * F).trace();
  return 0.5 * mu_ * (I1 - 3) + 0.25 * lambda_ * (J * J - 1) - (0.5 * lambda_ + mu_) * std::log(J);
}

Mat3 NeoHookean::first_piola(const Mat3& F) const {
  const double J = F.determinant();
  const Mat3 FinvT = F.inverse().transpose();
  return mu_ * F + (0.5 * lambda_ * (J * J - 1) - mu_) * FinvT;
}

// A_iJkL = mu d_ik d_JL + Lambda J^2 G_iJ G_kL - c G_iL G_kJ, with G = F^-T and
// c = Lambda/2 (J^2 - 1) - mu (from d(F^-T)_iJ/dF_kL = -G_iL G_kJ, d(J^2)/dF = 2 J^2 G).
void NeoHookean::first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const {
  const double J = F.determinant();
  const Mat3 G = F.inverse().transpose();
  const double c = 0.5 * lambda_ * (J * J - 1) - mu_;
  P = mu_ * F + c * G;
  const double lj2 = lambda_ * J * J;
  for (int i = 0; i < 3; ++i)
    for (int J_ = 0; J_ < 3; ++J_)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L)
          A[tangent_index(i, J_, k, L)] =
              mu_ * (i == k) * (J_ == L) + lj2 * G(i, J_) * G(k, L) - c * G(i, L) * G(k, J_);
}

}  // namespace stiction::materials
