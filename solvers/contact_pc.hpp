#pragma once
// The global level (33) of the paper's preconditioner, on the contact system (30)
//
//   M = [A  B1; B2  D] = [A  -B^T; C_u  C_lambda],   S_g = D - B2 A^-1 B1,
//
// in the four-factor form (8) or a block-triangular part of it, with A^-1 replaced by the
// inner preconditioner (HP (10), or MHP (11) with a pressure block) and S_g by
//
//   S~ = D + G,
//
// D exact on inactive nodes (identity), on slipping nodes' tangential rows (I_t, the
// elongation E^C and the angular term); G stands for B A^-1 B^T on the constrained
// directions (all of a sticking node, the normal of a slipping one), where the Schur
// complement is the inverse of a Steklov-Poincare operator. -<prefix>contact_schur picks G:
//
//   fractional (default): the order -1 model of fractional_schur.hpp, calibrated by the two
//              compliance estimates below; falls back to `mass` (auto scale) when the
//              estimates do not bracket (smooth <= diagonal). -<prefix>contact_fractional_form:
//              dense (its eigendecomposition; `mass` above -<prefix>contact_fractional_max_rows,
//              1500 rows), rational (rational_fractional_schur.hpp: sparse factorisations of
//              the surface, model error below -<prefix>contact_fractional_tol, 1e-2; one
//              process), or auto (default): dense up to max_rows, rational above it on one
//              process;
//   mass:      the paper's (32), G = s Pi M_lambda Pi.
//
// The paper gives no scale for (32); s has the units of a compliance, and the Schur
// complement's compliance spans a range: from the local stiffness of one surface element
// (~ h / E) up to the whole body's (~ L / E). Two estimates bracket it:
//   diagonal  s_d = sum_i (B2 diag(A)^-1 (-B1))_ii / sum_i (Pi M Pi)_ii over constrained rows
//             (the element end);
//   smooth    s_s = w^T B2 P_A^-1 (-B1) w / w^T (Pi M Pi) w, w ~ Pi 1 the smoothest
//             constrained field, P_A^-1 the inner preconditioner (the body end);
// and -<prefix>contact_scale picks s: auto (default) sqrt(s_d s_s), the geometric mean, which
// keeps the worst ratio of S~ to S_g over that range smallest; diagonal; smooth; or <x>
// (1 is the unscaled (32)). Measured with `mass`, schur-amg Krylov iterations per linear
// solve at levels 0 / 1 / 2 (reports/contact-schur-scale/, every contact scene there):
//                        s = 1               diagonal            smooth              auto
//   sliding-block-2d     20.3 / 23.6 / 24.5  20.4 / 24.9 / 29.7  19.2 / 21.5 / 21.3  17.7 / 19.9 / 20.7
//   hertz-cylinder-2d    45.8 / 57.6 / 70.8  19.4 / 23.2 / 30.6  31.8 / 40.6 / 49.4  18.6 / 21.2 / 24.2
//   contact-patch-2d     10.8 / 13.0 / 14.8  11.2 / 13.5 / 16.0  10.8 / 12.0 / 12.0  10.8 / 12.0 / 12.0
// A scalar s cannot follow a compliance that falls with the load's wave number: the
// fractional G can, and its counts stay flat under refinement (hertz-cylinder-2d 15.0 / 15.2
// / 15.4 with the full form; reports/contact-levels-0-2/).
//
// -<prefix>contact_fact picks the factorisation; it is PCFIELDSPLIT's
// -pc_fieldsplit_schur_fact_type with the same names and meaning. The level could be
// written as a PETSc Schur split (the displacement split's KSP a PCSHELL running HP / MHP,
// S~ given by PCFieldSplitSetSchurPre): it is kept by hand because PCFIELDSPLIT extracts
// the displacement block, nearly the whole Newton matrix, as a copy, where this level reads
// it in place. The fieldsplit-schur backend is the PETSc-only version, measured beside it:
//   full (the paper's (8) and (33)):
//     y = P_A^-1 r_a;  x_lambda = S~^-1 (r_lambda - B2 y);  x_a = P_A^-1 (r_a - B1 x_lambda)
//   upper (default): x_lambda = S~^-1 r_lambda;  x_a = P_A^-1 (r_a - B1 x_lambda)
//   lower: x_a = P_A^-1 r_a;  x_lambda = S~^-1 (r_lambda - B2 x_a)
// Choice: upper by default. It applies P_A^-1 once per Krylov iteration instead of twice, so
// an iteration costs what it costs without contact; it needs 10-20% more iterations than
// full, and is faster on every contact scene at levels 0-2 (schur-amg, time per linear solve
// against the same mesh without contact, worst level: full 1.37-2.38x, upper 1.11-1.98x;
// reports/contact-levels-0-2/ and contact-levels-0-2-upper/). Tried and not kept: a diagonal
// prediction of B2 P_A^-1 r_a in the upper form's multiplier solve (5-12% fewer iterations
// on the other contact scenes, none on hertz-spheres-3d at level 2; docs/method.md,
// "Choices beyond the paper").
// S~ is solved by its own KSP (<prefix>ss_, by default MUMPS's LU: it lives on the slave
// surface only, and its rows need pivoting, schur-levels-common.opts). With exact inner
// solves and S~ = S_g the full form is the exact inverse (tests/backends).
#include <memory>
#include <string>

#include "fractional_schur.hpp"
#include "hierarchical_pc.hpp"
#include "rational_fractional_schur.hpp"
#include "nonlinear/newton_system.hpp"

namespace stiction::solvers {

class ContactPreconditioner final : public ShellPreconditioner {
public:
  ContactPreconditioner(MPI_Comm comm, const std::string& prefix);

  // M: the whole contact system; inner must already be set up on it (it reads and writes
  // only the non-multiplier blocks of full-length vectors).
  // G is formed from the multiplier surface (multiplier_schur_parts.hpp): Pi M Pi, Pi K Pi
  // for the fractional model, and the slip rows' coupling, scaled like the mass.
  void setup(Mat M, IS multipliers, const nonlinear::MultiplierSurface& surface, const ShellPreconditioner& inner);
  void apply(Vec r, Vec x) const override;

  // Replaces S~ (e.g. the exact S_g in tests); after setup().
  void set_schur_operator(Mat S);
  void release();  // frees the blocks, S~ and its solver's set-up
  double copied_blocks_mb() const;  // B1, B2, D and S~
  double scale() const { return scale_; }
  // The two estimates the automatic scale combines (see above), from the last setup().
  struct ScaleEstimates {
    double diagonal = 0, smooth = 0;
  };
  ScaleEstimates scale_estimates() const { return estimates_; }
  // The fractional model's fit at the last setup(); fitted is false with the scaled mass.
  const FractionalFit& fractional_fit() const { return fit_; }
  KSP schur_solver() const { return ksp_ss_; }
  // S~ of the last setup(); with the rational fractional form, the scaled-mass S~ that
  // solve_schur corrects.
  Mat schur_approximation() const { return S_; }
  void solve_schur(Vec b, Vec x) const;  // x = S~^-1 b; b is overwritten
  Mat block(int row, int col) const;  // 0 = a (u, p), 1 = lambda

  enum class Factorisation { Full, Upper, Lower };

private:
  std::string option(const char* name, const char* fallback) const;  // -<prefix><name> as given, or fallback
  Factorisation factorisation_from_options() const;
  // G of the fractional model's dense form, or an empty handle: then S_ holds the scaled
  // mass (32), and rational_active_ says whether the rational form corrects its right sides.
  PetscMat fractional_from_options(Mat mass, Mat stiffness, Mat slip_coupling);
  double scale_from_options(Mat M, Mat mass);
  double diagonal_compliance(Mat M, Mat mass) const;
  double smooth_mode_compliance(Mat M, Mat mass) const;  // 0 when the probe gives no positive value

  std::string prefix_;
  const ShellPreconditioner* inner_ = nullptr;
  PetscKSP ksp_ss_;
  PetscIS is_a_, is_l_;
  PetscMat B1_, B2_, D_, S_;
  PetscVec work_, work2_, work_l_, work_a_;
  std::unique_ptr<RationalFractionalCorrection> rational_;
  bool rational_active_ = false;
  double scale_ = 1;
  Factorisation factorisation_ = Factorisation::Full;
  FractionalFit fit_;
  ScaleEstimates estimates_;
};

}  // namespace stiction::solvers
