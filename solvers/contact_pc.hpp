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
// multiplier mass. The paper gives no scale; s has the units of a compliance, and the
// Schur complement's compliance spans a range: from the local stiffness of one surface
// element (~ h / E) up to the whole body's (~ L / E). Two estimates bracket it:
//   diagonal  s_d = sum_i (B2 diag(A)^-1 (-B1))_ii / sum_i (Pi M Pi)_ii over constrained rows
//             (the element end);
//   smooth    s_s = w^T B2 P_A^-1 (-B1) w / w^T (Pi M Pi) w, w ~ Pi 1 the smoothest
//             constrained field, P_A^-1 the inner preconditioner (the body end);
// and -<prefix>contact_scale picks: auto (default) sqrt(s_d s_s), the geometric mean, which
// keeps the worst ratio of S~ to S_g over that range smallest; diagonal; smooth; or <x>
// (1 is the unscaled (32)). Measured, schur-amg Krylov iterations per linear solve at levels
// 0 / 1 / 2 (reports/contact-schur-scale/, every contact scene there):
//                        s = 1               diagonal            smooth              auto
//   sliding-block-2d     20.3 / 23.6 / 24.5  20.4 / 24.9 / 29.7  19.2 / 21.5 / 21.3  17.7 / 19.9 / 20.7
//   hertz-cylinder-2d    45.8 / 57.6 / 70.8  19.4 / 23.2 / 30.6  31.8 / 40.6 / 49.4  18.6 / 21.2 / 24.2
//   contact-patch-2d     10.8 / 13.0 / 14.8  11.2 / 13.5 / 16.0  10.8 / 12.2 / 14.0  10.8 / 12.0 / 12.0
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
  // The two estimates the automatic scale combines (see above), from the last setup().
  struct ScaleEstimates {
    double diagonal = 0, smooth = 0;
  };
  ScaleEstimates scale_estimates() const { return estimates_; }
  KSP schur_solver() const { return ksp_ss_; }
  Mat block(int row, int col) const;  // 0 = a (u, p), 1 = lambda

private:
  double scale_from_options(Mat M, Mat mass);
  double diagonal_compliance(Mat M, Mat mass) const;
  double smooth_mode_compliance(Mat M, Mat mass) const;  // 0 when the probe gives no positive value

  std::string prefix_;
  const ShellPreconditioner* inner_ = nullptr;
  PetscKSP ksp_ss_;
  PetscIS is_a_, is_l_;
  PetscMat B1_, B2_, D_, S_;
  PetscVec work_, work2_, work_l_, work_a_;
  double scale_ = 1;
  ScaleEstimates estimates_;
};

}  // namespace stiction::solvers
