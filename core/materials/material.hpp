#pragma once
// Hyperelastic material laws, total Lagrangian. Every law is written in 3D on the
// deformation gradient F; a 2D plane-strain problem embeds F with F_33 = 1 and keeps the
// in-plane components of P and of the tangent (see plane.hpp).
//
// Quantities per reference volume:
//   energy Psi(F), first Piola-Kirchhoff stress P = dPsi/dF = F S,
//   tangent A_iJkL = dP_iJ / dF_kL (81 entries, index ((i*3 + J)*3 + k)*3 + L).
// A mixed (displacement-pressure) law returns its moduli below; the assembly adds the
// pressure terms.
#include <Eigen/Dense>

#include <array>
#include <memory>
#include <string>

namespace stiction::materials {

using Mat3 = Eigen::Matrix3d;
using Tangent = std::array<double, 81>;
inline int tangent_index(int i, int J, int k, int L) { return ((i * 3 + J) * 3 + k) * 3 + L; }

class Material {
public:
  virtual ~Material() = default;
  virtual std::string name() const = 0;
  virtual std::string describe() const = 0;  // law and parameters, for reports
  virtual double energy(const Mat3& F) const = 0;
  virtual Mat3 first_piola(const Mat3& F) const = 0;
  virtual void first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const = 0;
  // Cauchy stress sigma = P F^T / J (the small-strain law returns its stress as is).
  virtual Mat3 cauchy(const Mat3& F) const { return first_piola(F) * F.transpose() / F.determinant(); }
  // True when the law is only valid for det F > 0 (finite strain).
  virtual bool requires_positive_jacobian() const { return true; }
  // Nearly incompressible laws solved in mixed displacement-pressure form (paper (2)-(5))
  // return their bulk modulus kappa > 0 here; energy, stress and tangent then describe
  // the isochoric part only, and the assembly adds -p J F^-T and the pressure equation.
  virtual double mixed_bulk_modulus() const { return 0; }
  // Mixed laws: the modulus of the isochoric part (mu10 for Mooney-Rivlin), the one the
  // paper's MHP (11) scales the pressure Schur complement by.
  virtual double mixed_shear_modulus() const { return 0; }
  // Small-strain Young's modulus: the stiffness scale of contact penalties and heuristics.
  virtual double reference_modulus() const = 0;
};

// Small-strain linear elasticity: P = lambda tr(eps) I + 2 mu eps, eps = sym(F - I).
class LinearElastic final : public Material {
public:
  LinearElastic(double E, double nu);
  std::string name() const override { return "linear"; }
  std::string describe() const override;
  double energy(const Mat3& F) const override;
  Mat3 first_piola(const Mat3& F) const override;
  void first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const override;
  Mat3 cauchy(const Mat3& F) const override { return first_piola(F); }
  bool requires_positive_jacobian() const override { return false; }
  double reference_modulus() const override { return E_; }

private:
  double E_, nu_, lambda_, mu_;
};

// Compressible Neo-Hookean, P = mu F + c(J) F^-T, in two forms that differ in the volumetric
// part (both reduce to linear elasticity with Lame's lambda and mu at small strain):
//   Wriggers' (paper Sec. 2.1, paper-notes 1):
//     Psi = mu/2 (I1 - 3) + Lambda/4 (J^2 - 1) - (Lambda/2 + mu) ln J,  c = Lambda/2 (J^2 - 1) - mu
//   Bonet & Wood's (most published ironing results use it):
//     Psi = mu/2 (I1 - 3) - mu ln J + Lambda/2 (ln J)^2,               c = Lambda ln J - mu
class NeoHookean final : public Material {
public:
  enum class Form { Wriggers, Bonet };
  NeoHookean(double E, double nu, Form form = Form::Wriggers);
  std::string name() const override { return form_ == Form::Wriggers ? "neo-hookean" : "neo-hookean-bonet"; }
  std::string describe() const override;
  double energy(const Mat3& F) const override;
  Mat3 first_piola(const Mat3& F) const override;
  void first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const override;
  double reference_modulus() const override { return E_; }

private:
  // c(J) and J dc/dJ of the stress above.
  void volumetric(double J, double& c, double& J_dc) const;

  double E_, nu_, lambda_, mu_;
  Form form_;
};

// Mooney-Rivlin (paper Sec. 2.2, paper-notes 1):
//   Psi = mu10 I3^(-1/3) I1 + mu01 I3^(-2/3) I2 [+ kappa/2 (J - 1)^2]
// Mixed form (the paper's): the bracket is replaced by the pressure p = -kappa (J - 1), an
// unknown of its own, and this class returns the isochoric part only. Displacement form:
// the bracket is included (locks as kappa/mu10 grows; kept for comparisons).
class MooneyRivlin final : public Material {
public:
  enum class Form { Mixed, Displacement };
  MooneyRivlin(double mu10, double mu01, double kappa, Form form);
  std::string name() const override { return form_ == Form::Mixed ? "mooney-rivlin" : "mooney-rivlin-displacement"; }
  std::string describe() const override;
  double energy(const Mat3& F) const override;
  Mat3 first_piola(const Mat3& F) const override;
  void first_piola_and_tangent(const Mat3& F, Mat3& P, Tangent& A) const override;
  double mixed_bulk_modulus() const override { return form_ == Form::Mixed ? kappa_ : 0.0; }
  double mixed_shear_modulus() const override { return form_ == Form::Mixed ? mu10_ : 0.0; }
  // Incompressible limit: shear modulus 2 (mu10 + mu01), E = 3 mu.
  double reference_modulus() const override { return 6 * (mu10_ + mu01_); }

private:
  double mu10_, mu01_, kappa_;
  Form form_;
};

// Lame parameters from Young's modulus and Poisson's ratio; throws on E <= 0 or
// nu outside (-1, 0.5).
void lame_parameters(double E, double nu, double& lambda, double& mu);

}  // namespace stiction::materials
