#pragma once
// The global level (33) of the paper's preconditioner, on the contact system (30)
//
//   M = [A  B1; B2  D] = [A  -B^T; C_u  C_lambda],   S_g = D - B2 A^-1 B1,
//
// in the full four-factor form (8) with A^-1 replaced by the inner preconditioner (HP (10),
// or MHP (11) with a pressure block) and S_g by the approximation (32):
//
//   S~ = D + s Pi M_lambda Pi
//
// D is exact on inactive nodes (identity), on slipping nodes' tangential rows (I_t, the
// elongation E^C and the angular term); Pi M_lambda Pi stands for B A^-1 B^T on the
// constrained directions (all of a sticking node, the normal of a slipping one): the Schur
// complement is the inverse of a Steklov-Poincare operator, spectrally close to a scaled
// multiplier mass. The paper gives no scale; s has the units of a compliance:
//   s = auto:  sum_i (B2 diag(A)^-1 (-B1))_ii / sum_i (Pi M Pi)_ii over constrained rows,
//   s = <x>:   that number (-<prefix>contact_scale; 1 is the unscaled (32)).
// S~ is solved by its own KSP (<prefix>ss_, a direct solve by default: it lives on the slave
// surface only).
//   y = P_A^-1 r_a;  x_lambda = S~^-1 (r_lambda - B2 y);  x_a = P_A^-1 (r_a - B1 x_lambda)
// With exact inner solves and S~ = S_g this is the exact inverse (tests/backends).
#include <string>

#include "hierarchical_pc.hpp"

namespace stiction::solvers {

class ContactPreconditioner final : public ShellPreconditioner {
public:
  ContactPreconditioner(MPI_Comm comm, const std::string& prefix);

  // M: the whole contact system; inner must already be set up on it (it reads and writes
  // only the non-multiplier blocks of full-length vectors).
  void setup(Mat M, IS multipliers, Mat schur_mass, const ShellPreconditioner& inner);
  void apply(Vec r, Vec x) const override;

  // Replaces S~ (e.g. the exact S_g in tests); after setup().
  void set_schur_operator(Mat S);
  double scale() const { return scale_; }
  KSP schur_solver() const { return ksp_ss_; }
  Mat block(int row, int col) const;  // 0 = a (u, p), 1 = lambda

private:
  double scale_from_options(Mat M, Mat mass) const;

  std::string prefix_;
  const ShellPreconditioner* inner_ = nullptr;
  PetscKSP ksp_ss_;
  PetscIS is_a_, is_l_;
  PetscMat B1_, B2_, D_, S_;
  PetscVec work_, work2_, work_l_, work_a_;
  double scale_ = 1;
};

}  // namespace stiction::solvers
