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

NeoHookean::NeoHookean(double E, double nu, Form form) : E_(E), nu_(nu), form_(form) {
  lame_parameters(E, nu, lambda_, mu_);
}

std::string NeoHookean::describe() const {
  return fmt::format("compressible Neo-Hookean, {} form (E = {:g}, nu = {:g}; mu = {:g}, Lambda = {:g})",
                     form_ == Form::Wriggers ? "Wriggers'" : "Bonet's", E_, nu_, mu_, lambda_);
}

void NeoHookean::volumetric(double J, double& c, double& J_dc) const {
  if (form_ == Form::Wriggers) {
    c = 0.5 * lambda_ * (J * J - 1) - mu_;
    J_dc = lambda_ * J * J;
  } else {
    c = lambda_ * std::log(J) - mu_;
    J_dc = lambda_;
  }
}

double NeoHookean::energy(const Mat3& F) const {
  const double J = F.determinant(), lnJ = std::log(J);
  const double I1 = (F.transpose() * F).trace();
  const double volumetric = form_ == Form::Wriggers ? 0.25 * lambda_ * (J * J - 1) - (0.5 * lambda_ + mu_) * lnJ
                                                    : -mu_ * lnJ + 0.5 * lambda_ * lnJ * lnJ;
  return 0.5 * mu_ * (I1 - 3) + volumetric;
}

Mat3 NeoHookean::first_piola(const Mat3& F) const {
  double c, J_dc;
  volumetric(F.determinant(), c, J_dc);
  return mu_ * F + c * F.inverse().transpose();
}

// A_iJkL = mu d_ik d_JL + J c'(J) G_iJ G_kL - c G_iL G_kJ, with G = F^-T (from
// d(F^-T)_iJ/dF_kL = -G_iL G_kJ and dJ/dF = J G).
void NeoHookean::first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const {
  const Mat3 G = F.inverse().transpose();
  double c, J_dc;
  volumetric(F.determinant(), c, J_dc);
  P = mu_ * F + c * G;
  for (int i = 0; i < 3; ++i)
    for (int J_ = 0; J_ < 3; ++J_)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L)
          A[tangent_index(i, J_, k, L)] =
              mu_ * (i == k) * (J_ == L) + J_dc * G(i, J_) * G(k, L) - c * G(i, L) * G(k, J_);
}

MooneyRivlin::MooneyRivlin(double mu10, double mu01, double kappa, Form form)
    : mu10_(mu10), mu01_(mu01), kappa_(kappa), form_(form) {
  if (!(mu10 > 0) || !(mu01 >= 0) || !(kappa > 0))
    throw Error(fmt::format("Mooney-Rivlin needs mu10 > 0, mu01 >= 0, kappa > 0 (got {}, {}, {})", mu10, mu01, kappa));
}

std::string MooneyRivlin::describe() const {
  return fmt::format("Mooney-Rivlin, {} form (mu10 = {:g}, mu01 = {:g}, kappa = {:g}; small-strain shear modulus {:g})",
                     form_ == Form::Mixed ? "mixed u-p" : "displacement", mu10_, mu01_, kappa_, 2 * (mu10_ + mu01_));
}

double MooneyRivlin::energy(const Mat3& F) const {
  const double J = F.determinant();
  const Mat3 C = F.transpose() * F;
  const double I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C.array() * C.array()).sum());
  const double iso = mu10_ * std::pow(J, -2.0 / 3) * I1 + mu01_ * std::pow(J, -4.0 / 3) * I2;
  return form_ == Form::Mixed ? iso : iso + 0.5 * kappa_ * (J - 1) * (J - 1);
}

// With a = J^(-2/3), b = J^(-4/3), G = F^-T:
//   P' = mu10 (2a F - 2/3 a I1 G) + mu01 (2b (I1 F - F C) - 4/3 b I2 G)   (= 2 F dPsi'/dC)
//   P_vol = kappa (J - 1) J G                                           (displacement form)
Mat3 MooneyRivlin::first_piola(const Mat3& F) const {
  Mat3 P;
  Tangent unused;
  first_piola_and_tangent(F, P, unused);
  return P;
}

// Tangent from d a = -2/3 a G_kL, d b = -4/3 b G_kL, d I1 = 2 F_kL, d I2 = 2 I1 F_kL - 2 (FC)_kL,
// d G_iJ = -G_iL G_kJ, d (FC)_iJ = d_ik C_LJ + F_iL F_kJ + (F F^T)_ik d_JL (all per dF_kL).
void MooneyRivlin::first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const {
  const double J = F.determinant();
  const Mat3 G = F.inverse().transpose();
  const Mat3 C = F.transpose() * F, FC = F * C, FFt = F * F.transpose();
  const double I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C.array() * C.array()).sum());
  const double a = std::pow(J, -2.0 / 3), b = std::pow(J, -4.0 / 3);
  P = mu10_ * (2 * a * F - (2.0 / 3) * a * I1 * G) + mu01_ * (2 * b * (I1 * F - FC) - (4.0 / 3) * b * I2 * G);
  const bool vol = form_ == Form::Displacement;
  if (vol) P += kappa_ * (J - 1) * J * G;
  for (int i = 0; i < 3; ++i)
    for (int Jx = 0; Jx < 3; ++Jx)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L) {
          const double dik = i == k, dJL = Jx == L;
          const double dT1 = 2 * (-(2.0 / 3) * a * G(k, L) * F(i, Jx) + a * dik * dJL);
          const double dT2 = -(2.0 / 3) * (-(2.0 / 3) * a * G(k, L) * I1 * G(i, Jx) + a * 2 * F(k, L) * G(i, Jx) -
                                            a * I1 * G(i, L) * G(k, Jx));
          const double dT3 = 2 * (-(4.0 / 3) * b * G(k, L) * (I1 * F(i, Jx) - FC(i, Jx)) +
                                  b * (2 * F(k, L) * F(i, Jx) + I1 * dik * dJL - dik * C(L, Jx) - F(i, L) * F(k, Jx) -
                                       FFt(i, k) * dJL));
          const double dT4 = -(4.0 / 3) * (-(4.0 / 3) * b * G(k, L) * I2 * G(i, Jx) +
                                            b * (2 * I1 * F(k, L) - 2 * FC(k, L)) * G(i, Jx) - b * I2 * G(i, L) * G(k, Jx));
          double value = mu10_ * (dT1 + dT2) + mu01_ * (dT3 + dT4);
          if (vol) value += kappa_ * ((2 * J - 1) * J * G(k, L) * G(i, Jx) - (J - 1) * J * G(i, L) * G(k, Jx));
          A[tangent_index(i, Jx, k, L)] = value;
        }
}

}  // namespace stiction::materials
