#pragma once
// MHP, the paper's mixed preconditioner (11), on the displacement-pressure system
//
//   M = [A  Bp^T; Bp  C],   C = -(1/kappa) M_p,   S_p = C - Bp A^-1 Bp^T,
//
// with A^-1 replaced by HP (10) and S_p by alpha M_p, alpha = -(1/mu10 + 1/kappa) (same
// sign as S_p), applied with one SSOR sweep.
//   Form Upper, (11):  y_p = S~^-1 r_p,  x_u = HP (r_u - Bp^T y_p),  x_p = y_p
//   Form Full, (8):    y_u = HP r_u,  x_p = S~^-1 (r_p - Bp y_u),  x_u = HP (r_u - Bp^T x_p)
// With exact inner solves (HP exact, S~ = S_p) Full is the exact inverse (tests/backends).
// -<prefix>mhp_fact upper | full chooses the form at setup (default: set_form's, Upper).
// The displacement and pressure unknowns are given as index sets (on several processes
// neither is a contiguous range); other unknowns of A (contact multipliers) are left alone.
#include <string>

#include "hierarchical_pc.hpp"

namespace stiction::solvers {

class MixedPreconditioner final : public ShellPreconditioner {
public:
  MixedPreconditioner(MPI_Comm comm, const std::string& prefix, const HierarchicalPreconditioner& hp);

  // A: the whole mixed matrix; HP must already be set up on it. S~ = alpha M_p, M_p in the
  // pressure block's numbering (rows in the order of `pressure`, process by process), alpha
  // from the mixed law's moduli (pressure_schur_scale).
  void setup(Mat A, IS displacement, IS pressure, Mat pressure_mass, double shear_modulus, double bulk_modulus);
  // alpha of (11): -(1/mu10 + 1/kappa), the sign of S_p.
  static double pressure_schur_scale(double shear_modulus, double bulk_modulus);
  void apply(Vec r, Vec x) const override;

  void set_form(SchurForm form) { form_ = form; }  // Upper (default) or Full
  // Replaces the pressure Schur approximation (e.g. the exact S_p in tests); after setup().
  void set_pressure_operator(Mat S);
  void release();  // frees the coupling blocks
  double copied_blocks_mb() const;  // storage of the blocks held as copies (S~ included)
  KSP pressure_solver() const { return ksp_pp_; }

private:
  const HierarchicalPreconditioner& hp_;
  std::string prefix_;
  PetscKSP ksp_pp_;
  PetscIS is_u_, is_p_;
  PetscMat A_up_, A_pu_, S_;
  PatternKey pattern_;  // of the matrix the coupling blocks were extracted from
  PetscVec work_, work2_, work_p_, work_u_;
  SchurForm form_ = SchurForm::Upper;
};

}  // namespace stiction::solvers
