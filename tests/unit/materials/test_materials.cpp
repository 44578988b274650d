// Stress = derivative of the energy and tangent = derivative of the stress, by central
// finite differences (relative 1e-6); Neo-Hookean reduces to linear elasticity at small
// strain.
#include <gtest/gtest.h>

#include <memory>

#include "materials/material.hpp"

namespace stiction::materials {
namespace {

Mat3 sample_deformation(double scale) {
  Mat3 H;
  H << 0.11, -0.04, 0.07, 0.02, -0.09, 0.05, -0.06, 0.03, 0.13;
  return Mat3::Identity() + scale * H;
}

std::unique_ptr<Material> make(const std::string& name) {
  if (name == "linear") return std::make_unique<LinearElastic>(200.0, 0.3);
  if (name == "mooney-rivlin") return std::make_unique<MooneyRivlin>(1.0, 0.1, 100.0, MooneyRivlin::Form::Mixed);
  if (name == "mooney-rivlin-displacement")
    return std::make_unique<MooneyRivlin>(1.0, 0.1, 100.0, MooneyRivlin::Form::Displacement);
  if (name == "neo-hookean-bonet") return std::make_unique<NeoHookean>(200.0, 0.3, NeoHookean::Form::Bonet);
  return std::make_unique<NeoHookean>(200.0, 0.3);
}

class MaterialLaw : public ::testing::TestWithParam<std::string> {};

TEST_P(MaterialLaw, StressIsEnergyDerivative) {
  const auto law = make(GetParam());
  const Mat3 F = sample_deformation(2.0);
  const Mat3 P = law->first_piola(F);
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i)
    for (int J = 0; J < 3; ++J) {
      Mat3 Fp = F, Fm = F;
      Fp(i, J) += h;
      Fm(i, J) -= h;
      const double fd = (law->energy(Fp) - law->energy(Fm)) / (2 * h);
      EXPECT_NEAR(P(i, J), fd, 1e-6 * P.norm()) << i << J;
    }
}

TEST_P(MaterialLaw, TangentIsStressDerivative) {
  const auto law = make(GetParam());
  const Mat3 F = sample_deformation(2.0);
  Mat3 P;
  Tangent A;
  law->first_piola_and_tangent(F, P, A);
  EXPECT_LT((P - law->first_piola(F)).norm(), 1e-14 * P.norm());
  double a_norm = 0;
  for (double a : A) a_norm = std::max(a_norm, std::abs(a));
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k)
    for (int L = 0; L < 3; ++L) {
      Mat3 Fp = F, Fm = F;
      Fp(k, L) += h;
      Fm(k, L) -= h;
      const Mat3 dP = (law->first_piola(Fp) - law->first_piola(Fm)) / (2 * h);
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J) EXPECT_NEAR(A[tangent_index(i, J, k, L)], dP(i, J), 1e-6 * a_norm);
    }
}

TEST_P(MaterialLaw, StressFreeAtIdentity) {
  EXPECT_LT(make(GetParam())->first_piola(Mat3::Identity()).norm(), 1e-13);
}

INSTANTIATE_TEST_SUITE_P(Laws, MaterialLaw,
                         ::testing::Values("linear", "neo-hookean", "neo-hookean-bonet", "mooney-rivlin",
                                           "mooney-rivlin-displacement"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

class NeoHookeanForm : public ::testing::TestWithParam<NeoHookean::Form> {};

TEST_P(NeoHookeanForm, MatchesLinearElasticityAtSmallStrain) {
  const NeoHookean nh(200.0, 0.3, GetParam());
  const LinearElastic lin(200.0, 0.3);
  for (double scale : {1e-4, 1e-6}) {
    const Mat3 F = sample_deformation(scale);
    const Mat3 p_nh = nh.first_piola(F), p_lin = lin.first_piola(F);
    // The difference is second order in the strain: relative O(scale).
    EXPECT_LT((p_nh - p_lin).norm(), 2 * scale * p_lin.norm()) << "scale " << scale;
  }
  Mat3 P;
  Tangent a_nh, a_lin;
  nh.first_piola_and_tangent(Mat3::Identity(), P, a_nh);
  lin.first_piola_and_tangent(Mat3::Identity(), P, a_lin);
  for (int k = 0; k < 81; ++k) EXPECT_NEAR(a_nh[k], a_lin[k], 1e-12 * 200);
}

INSTANTIATE_TEST_SUITE_P(Forms, NeoHookeanForm, ::testing::Values(NeoHookean::Form::Wriggers, NeoHookean::Form::Bonet));

// The two forms share the deviatoric part and differ in the volumetric one: under a pure
// dilation F = s I, P = (mu s + c(s^3) / s) I with c = Lambda ln J - mu (Bonet) or
// Lambda/2 (J^2 - 1) - mu (Wriggers).
TEST(NeoHookean, FormsDifferInTheVolumetricPartOnly) {
  const double s = 1.1, J = s * s * s;
  double lambda, mu;
  lame_parameters(200.0, 0.3, lambda, mu);
  const Mat3 F = s * Mat3::Identity();
  const Mat3 P_bonet = NeoHookean(200.0, 0.3, NeoHookean::Form::Bonet).first_piola(F);
  const Mat3 P_wriggers = NeoHookean(200.0, 0.3).first_piola(F);
  EXPECT_NEAR(P_bonet(0, 0), mu * s + (lambda * std::log(J) - mu) / s, 1e-12 * mu);
  EXPECT_NEAR(P_wriggers(0, 0), mu * s + (0.5 * lambda * (J * J - 1) - mu) / s, 1e-12 * mu);
  // Isochoric shear (det F = 1): the volumetric parts vanish alike.
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.3;
  EXPECT_LT((NeoHookean(200.0, 0.3, NeoHookean::Form::Bonet).first_piola(shear) -
             NeoHookean(200.0, 0.3).first_piola(shear)).norm(), 1e-12 * mu);
}

TEST(NeoHookean, CauchyStressIsSymmetric) {
  const Mat3 s = NeoHookean(200.0, 0.3).cauchy(sample_deformation(3.0));
  EXPECT_LT((s - s.transpose()).norm(), 1e-12 * s.norm());
}

// The isochoric Mooney-Rivlin stress is deviatoric in the Cauchy sense: tr(sigma') = 0,
// so the pressure unknown carries all of the hydrostatic stress.
TEST(MooneyRivlin, IsochoricCauchyStressIsTraceFree) {
  const MooneyRivlin mr(1.0, 0.1, 100.0, MooneyRivlin::Form::Mixed);
  const Mat3 s = mr.cauchy(sample_deformation(3.0));
  EXPECT_LT(std::abs(s.trace()), 1e-12 * s.norm());
  EXPECT_GT(s.norm(), 0.1);
}

TEST(Materials, RejectInvalidParameters) {
  EXPECT_ANY_THROW(NeoHookean(-1.0, 0.3));
  EXPECT_ANY_THROW(LinearElastic(1.0, 0.5));
}

}  // namespace
}  // namespace stiction::materials
