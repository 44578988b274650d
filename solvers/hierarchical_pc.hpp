#pragma once
// HP, the paper's hierarchical preconditioner (10), on the P2 displacement system split as
// [u_l | u_q] (vertex hats | edge corrections):
//
//   A = [A_ll A_lq; A_ql A_qq],   S = A_qq - A_ql A_ll^-1 A_lq.
//
// Form Lower (the reading of (10) in paper-notes.md sec. 3; (10) as printed would return
// x_l = r_l untouched):
//   x_l = A_ll^-1 r_l,   x_q = S~^-1 (r_q - A_ql x_l)
// Form Full, the four-factor inverse (8) with A^-1 -> A_ll^-1:
//   y_l = A_ll^-1 r_l,  x_q = S~^-1 (r_q - A_ql y_l),  x_l = A_ll^-1 (r_l - A_lq x_q)
// With exact sub-solves and S~ = S, Full is the exact inverse (tests/backends).
// PETSc has both forms: Lower is PCFIELDSPLIT of type multiplicative over (u_l, u_q) with
// the qq split's operator replaced by S~ (block Gauss-Seidel), Full is PCFIELDSPLIT of type
// schur with -pc_fieldsplit_schur_fact_type full and a user Schur operator. They are kept
// here because S~ is the paper's (A_qq, or its SOR sweep, not an assembled selfp) and the
// blocks are views of the Newton matrix (PCFIELDSPLIT copies every block); the generic
// PETSc split over the whole displacement is the fieldsplit-schur backend.
//
// A_ll^-1 and S~^-1 are inner KSPs with their own option prefixes (<prefix>ll_, <prefix>qq_):
// the paper's choices are a direct solve (or one AMG V-cycle) on A_ll and one SSOR sweep
// on A_qq. A_ll is copied out of A (AMG and LU need its entries); A_ql, A_lq and, when the
// qq preconditioner needs no more than SOR does, A_qq are views of A (block_view.hpp).
#include <string>

#include "common/petsc.hpp"

namespace stiction::solvers {

enum class SchurForm { Lower, Upper, Full };

// The form named by the option -<prefix><key> (one of two values), else `current`; any other
// value is an Error naming the option.
struct SchurFormChoice {
  const char* name;
  SchurForm form;
};
SchurForm schur_form_from_options(const std::string& prefix, const char* key, SchurFormChoice first,
                                  SchurFormChoice second, SchurForm current);

// A preconditioner applied through a PETSc PCSHELL (HP, MHP, and the contact level).
class ShellPreconditioner {
public:
  virtual ~ShellPreconditioner() = default;
  virtual void apply(Vec r, Vec x) const = 0;  // x = P^-1 r
};

// Installs p as the PCSHELL of pc under a descriptive name (p must outlive the PC).
void use_as_shell(PC pc, const ShellPreconditioner& p, const char* name);

class HierarchicalPreconditioner final : public ShellPreconditioner {
public:
  HierarchicalPreconditioner(MPI_Comm comm, const std::string& prefix);

  // Extracts the blocks of A and sets up both sub-solvers. near_null_space (may be null)
  // is restricted to u_l and handed to the A_ll solver; block_size (dim) reaches AMG.
  void setup(Mat A, IS linear, IS quadratic, MatNullSpace near_null_space, int block_size);
  // Writes x's u_l and u_q parts only (other blocks of x are left as they are).
  void apply(Vec r, Vec x) const override;

  // Lower (default) or Full; -<prefix>hp_fact lower|full, when given, overrides it at set-up.
  void set_form(SchurForm form) { form_ = form; }
  SchurForm form() const { return form_; }
  // Replaces the operator of the quadratic-block solver (default A_qq), e.g. by the exact
  // Schur complement in verification tests. Call after setup().
  void set_quadratic_operator(Mat S);
  // Frees the blocks and both sub-solvers' set-ups (LinearSolver::release).
  void release();

  KSP linear_solver() const { return ksp_ll_; }
  KSP quadratic_solver() const { return ksp_qq_; }
  // 0 = l, 1 = q (A_lq exists for Full only); a view (MatMult, SOR) or a copy, see above.
  Mat block(int row, int col) const;
  double copied_blocks_mb() const;  // storage of the blocks held as copies

private:
  std::string prefix_;
  PetscKSP ksp_ll_, ksp_qq_;
  PetscIS is_l_, is_q_;
  PetscMat A_ll_, A_lq_, A_ql_, A_qq_;
  PatternKey pattern_;  // of the matrix the blocks were extracted from
  PetscVec work_q_, work_l_, work_l2_;
  SchurForm form_ = SchurForm::Lower;
};

}  // namespace stiction::solvers
