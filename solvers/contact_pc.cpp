#include "contact_pc.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "common/error.hpp"
#include "field_sets.hpp"
#include "multiplier_schur_parts.hpp"
#include "rational_fractional_schur.hpp"
#include "solver_figures.hpp"

namespace stiction::solvers {

ContactPreconditioner::ContactPreconditioner(MPI_Comm comm, const std::string& prefix) : prefix_(prefix) {
  STICTION_PETSC(KSPCreate(comm, ksp_ss_.out()));
  STICTION_PETSC(KSPSetOptionsPrefix(ksp_ss_, (prefix + "ss_").c_str()));
}

std::string ContactPreconditioner::option(const char* name, const char* fallback) const {
  char value[64];
  PetscBool set;
  STICTION_PETSC(PetscOptionsGetString(nullptr, prefix_.c_str(), name, value, sizeof value, &set));
  return set ? value : fallback;
}

double ContactPreconditioner::scale_from_options(Mat M, Mat mass) {
  const std::string v = option("-contact_scale", "auto");
  estimates_.diagonal = diagonal_compliance(M, mass);
  estimates_.smooth = smooth_mode_compliance(M, mass);
  if (v == "auto")
    return estimates_.smooth > 0 ? std::sqrt(estimates_.diagonal * estimates_.smooth) : estimates_.diagonal;
  if (v == "diagonal") return estimates_.diagonal;
  if (v == "smooth") return estimates_.smooth > 0 ? estimates_.smooth : estimates_.diagonal;
  char* end;
  const double number = std::strtod(v.c_str(), &end);
  if (*end || !(number > 0))
    throw Error(fmt::format("-{}contact_scale: '{}' is none of auto, diagonal, smooth or a positive number", prefix_,
                            v));
  return number;
}

ContactPreconditioner::Factorisation ContactPreconditioner::factorisation_from_options() const {
  const std::string v = option("-contact_fact", "upper");
  if (v == "full") return Factorisation::Full;
  if (v == "upper") return Factorisation::Upper;
  if (v == "lower") return Factorisation::Lower;
  throw Error(fmt::format("-{}contact_fact: '{}' is none of full, upper or lower", prefix_, v));
}

PetscMat ContactPreconditioner::fractional_from_options(Mat mass, Mat stiffness, Mat slip_coupling) {
  fit_ = {};
  rational_active_ = false;
  const std::string v = option("-contact_schur", "fractional");
  if (v == "mass") return {};
  if (v != "fractional") throw Error(fmt::format("-{}contact_schur: '{}' is neither mass nor fractional", prefix_, v));
  const std::string form = option("-contact_fractional_form", "auto");
  if (form != "auto" && form != "dense" && form != "rational")
    throw Error(fmt::format("-{}contact_fractional_form: '{}' is none of auto, dense or rational", prefix_, form));
  PetscInt max_rows = 1500, dim;
  PetscBool set;
  STICTION_PETSC(PetscOptionsGetInt(nullptr, prefix_.c_str(), "-contact_fractional_max_rows", &max_rows, &set));
  STICTION_PETSC(ISGetBlockSize(is_l_, &dim));
  if (form != "rational") {
    PetscMat G = fractional_compliance(mass, stiffness, static_cast<int>(dim), estimates_.diagonal,
                                       estimates_.smooth, static_cast<int>(max_rows), fit_);
    PetscMPIInt processes;
    MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(mass)), &processes);
    if (G || form == "dense" || fit_.rows <= max_rows || processes > 1) return G;
  }
  // The rational form: S~ solved through the scaled mass's S~ and a right-side correction.
  PetscReal tolerance = 1e-2;
  STICTION_PETSC(PetscOptionsGetReal(nullptr, prefix_.c_str(), "-contact_fractional_tol", &tolerance, &set));
  if (!(tolerance > 0 && tolerance < 0.5))
    throw Error(fmt::format("-{}contact_fractional_tol: {} is not in (0, 0.5)", prefix_, tolerance));
  if (!rational_) rational_ = std::make_unique<RationalFractionalCorrection>();
  rational_active_ = rational_->setup(mass, stiffness, D_, slip_coupling, static_cast<int>(dim), scale_,
                                      estimates_.diagonal, estimates_.smooth, tolerance, fit_);
  return {};
}

double ContactPreconditioner::diagonal_compliance(Mat M, Mat mass) const {
  // s = sum diag(B2 diag(A)^-1 (-B1)) / sum diag(Pi M Pi), over rows where the mass is nonzero.
  PetscVec dA, dA_inv;
  STICTION_PETSC(MatCreateVecs(M, nullptr, dA.out()));
  STICTION_PETSC(MatGetDiagonal(M, dA));
  Vec dA_a;
  STICTION_PETSC(VecGetSubVector(dA, is_a_, &dA_a));
  STICTION_PETSC(VecDuplicate(dA_a, dA_inv.out()));
  STICTION_PETSC(VecCopy(dA_a, dA_inv));
  STICTION_PETSC(VecRestoreSubVector(dA, is_a_, &dA_a));
  STICTION_PETSC(VecReciprocal(dA_inv));
  PetscMat scaled, product;
  STICTION_PETSC(MatDuplicate(B1_, MAT_COPY_VALUES, scaled.out()));
  STICTION_PETSC(MatDiagonalScale(scaled, dA_inv, nullptr));
  STICTION_PETSC(MatMatMult(B2_, scaled, MAT_INITIAL_MATRIX, PETSC_DEFAULT, product.out()));
  PetscVec dp, dm;
  STICTION_PETSC(MatCreateVecs(mass, dm.out(), dp.out()));
  STICTION_PETSC(MatGetDiagonal(product, dp));
  STICTION_PETSC(MatGetDiagonal(mass, dm));
  const PetscScalar *p, *m;
  PetscInt n;
  STICTION_PETSC(VecGetLocalSize(dm, &n));
  STICTION_PETSC(VecGetArrayRead(dp, &p));
  STICTION_PETSC(VecGetArrayRead(dm, &m));
  double num = 0, den = 0;
  for (PetscInt i = 0; i < n; ++i)
    if (m[i] > 0) num -= p[i], den += m[i];
  STICTION_PETSC(VecRestoreArrayRead(dp, &p));
  STICTION_PETSC(VecRestoreArrayRead(dm, &m));
  double sums[2] = {num, den};
  MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, PetscObjectComm(reinterpret_cast<PetscObject>(mass)));
  return sums[1] > 0 && sums[0] > 0 ? sums[0] / sums[1] : 1.0;
}

double ContactPreconditioner::smooth_mode_compliance(Mat M, Mat mass) const {
  // w ~ Pi 1: the constrained directions of every node, as smooth as the surface allows.
  PetscVec ones, w, row_sum, v, full, y;
  STICTION_PETSC(MatCreateVecs(mass, ones.out(), w.out()));
  STICTION_PETSC(VecDuplicate(w, row_sum.out()));
  STICTION_PETSC(VecSet(ones, 1.0));
  STICTION_PETSC(MatMult(mass, ones, w));
  {
    // Row sums of |Pi M Pi|.
    PetscInt first, last;
    STICTION_PETSC(MatGetOwnershipRange(mass, &first, &last));
    for (PetscInt row = first; row < last; ++row) {
      PetscInt ncols;
      const PetscScalar* values;
      STICTION_PETSC(MatGetRow(mass, row, &ncols, nullptr, &values));
      double sum = 0;
      for (PetscInt k = 0; k < ncols; ++k) sum += std::abs(values[k]);
      STICTION_PETSC(MatRestoreRow(mass, row, &ncols, nullptr, &values));
      STICTION_PETSC(VecSetValue(row_sum, row, sum, INSERT_VALUES));
    }
    STICTION_PETSC(VecAssemblyBegin(row_sum));
    STICTION_PETSC(VecAssemblyEnd(row_sum));
  }
  {
    PetscScalar* a;
    const PetscScalar* r;
    PetscInt n;
    STICTION_PETSC(VecGetLocalSize(w, &n));
    STICTION_PETSC(VecGetArray(w, &a));
    STICTION_PETSC(VecGetArrayRead(row_sum, &r));
    for (PetscInt i = 0; i < n; ++i) a[i] = r[i] > 0 ? a[i] / r[i] : 0.0;
    STICTION_PETSC(VecRestoreArrayRead(row_sum, &r));
    STICTION_PETSC(VecRestoreArray(w, &a));
  }
  // s = -w^T B2 P_A^-1 B1 w / w^T (Pi M Pi) w.
  STICTION_PETSC(MatCreateVecs(M, full.out(), y.out()));
  STICTION_PETSC(VecZeroEntries(full));
  Vec full_a;
  STICTION_PETSC(VecGetSubVector(full, is_a_, &full_a));
  STICTION_PETSC(MatMult(B1_, w, full_a));
  STICTION_PETSC(VecRestoreSubVector(full, is_a_, &full_a));
  STICTION_PETSC(VecZeroEntries(y));
  inner_->apply(full, y);
  Vec y_a;
  STICTION_PETSC(MatCreateVecs(B2_, nullptr, v.out()));
  STICTION_PETSC(VecGetSubVector(y, is_a_, &y_a));
  STICTION_PETSC(MatMult(B2_, y_a, v));
  STICTION_PETSC(VecRestoreSubVector(y, is_a_, &y_a));
  PetscScalar numerator, denominator;
  STICTION_PETSC(VecDot(v, w, &numerator));
  STICTION_PETSC(MatMult(mass, w, row_sum));
  STICTION_PETSC(VecDot(row_sum, w, &denominator));
  return denominator > 0 && -numerator > 0 ? -numerator / denominator : 0.0;
}

void ContactPreconditioner::setup(Mat M, IS multipliers, const nonlinear::MultiplierSurface& surface,
                                  const ShellPreconditioner& inner) {
  const MultiplierSchurParts parts = form_multiplier_schur_parts(surface);
  inner_ = &inner;
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(multipliers)));
  *is_l_.out() = multipliers;
  is_a_ = complement_in(M, multipliers);
  // The contact blocks change pattern with the active set: extracted afresh every time.
  STICTION_PETSC(MatCreateSubMatrix(M, is_a_, is_l_, MAT_INITIAL_MATRIX, B1_.out()));
  STICTION_PETSC(MatCreateSubMatrix(M, is_l_, is_a_, MAT_INITIAL_MATRIX, B2_.out()));
  STICTION_PETSC(MatCreateSubMatrix(M, is_l_, is_l_, MAT_INITIAL_MATRIX, D_.out()));
  scale_ = scale_from_options(M, parts.mass);
  factorisation_ = factorisation_from_options();
  STICTION_PETSC(MatDuplicate(D_, MAT_COPY_VALUES, S_.out()));
  if (PetscMat G = fractional_from_options(parts.mass, parts.laplacian, parts.slip_coupling); G)
    STICTION_PETSC(MatAXPY(S_, 1.0, G, DIFFERENT_NONZERO_PATTERN));
  else  // also the rational form's S_m
    STICTION_PETSC(MatAXPY(S_, scale_, parts.mass, DIFFERENT_NONZERO_PATTERN));
  STICTION_PETSC(MatAXPY(S_, scale_, parts.slip_coupling, DIFFERENT_NONZERO_PATTERN));
  // PETSc 3.18's LU with inodes and a fill-reducing ordering (nd, rcm) met a zero pivot and
  // NaNs on the fractional model's dense block of a symmetric positive definite S~
  // (sliding-block-2d, level 0): without inodes, or in natural order, it factors.
  STICTION_PETSC(MatSetOption(S_, MAT_USE_INODES, PETSC_FALSE));
  STICTION_PETSC(MatAssemblyBegin(S_, MAT_FINAL_ASSEMBLY));  // drops the inodes found before
  STICTION_PETSC(MatAssemblyEnd(S_, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(KSPSetOperators(ksp_ss_, S_, S_));
  STICTION_PETSC(KSPSetFromOptions(ksp_ss_));
  STICTION_PETSC(KSPSetUp(ksp_ss_));
  STICTION_PETSC(MatCreateVecs(M, work_.out(), work2_.out()));
  STICTION_PETSC(MatCreateVecs(D_, work_l_.out(), nullptr));
  STICTION_PETSC(MatCreateVecs(B1_, nullptr, work_a_.out()));
}

double ContactPreconditioner::copied_blocks_mb() const {
  return aij_storage_mb(B1_) + aij_storage_mb(B2_) + aij_storage_mb(D_) + aij_storage_mb(S_);
}

void ContactPreconditioner::release() {
  STICTION_PETSC(KSPReset(ksp_ss_));
  B1_.reset(), B2_.reset(), D_.reset(), S_.reset();
  rational_.reset();
  rational_active_ = false;
}

void ContactPreconditioner::set_schur_operator(Mat S) {
  rational_active_ = false;
  STICTION_PETSC(KSPSetOperators(ksp_ss_, S, S));
  STICTION_PETSC(KSPSetUp(ksp_ss_));
}

Mat ContactPreconditioner::block(int row, int col) const {
  if (row == 0) return col == 1 ? B1_.get() : nullptr;
  return col == 0 ? B2_.get() : D_.get();
}

void ContactPreconditioner::solve_schur(Vec b, Vec x) const {
  if (rational_active_) rational_->correct(b, b);
  STICTION_PETSC(KSPSolve(ksp_ss_, b, x));
}

void ContactPreconditioner::apply(Vec r, Vec x) const {
  // work_l_ = r_lambda - B2 y with y = P_A^-1 r_a (full, lower), or r_lambda (upper).
  Vec y_a, r_l, x_l;
  STICTION_PETSC(VecGetSubVector(r, is_l_, &r_l));
  if (factorisation_ == Factorisation::Upper) {
    STICTION_PETSC(VecCopy(r_l, work_l_));
  } else {
    STICTION_PETSC(VecZeroEntries(work_));
    inner_->apply(r, work_);
    STICTION_PETSC(VecGetSubVector(work_, is_a_, &y_a));
    STICTION_PETSC(MatMult(B2_, y_a, work_l_));
    STICTION_PETSC(VecRestoreSubVector(work_, is_a_, &y_a));
    STICTION_PETSC(VecAYPX(work_l_, -1.0, r_l));
  }
  STICTION_PETSC(VecRestoreSubVector(r, is_l_, &r_l));
  STICTION_PETSC(VecGetSubVector(x, is_l_, &x_l));
  solve_schur(work_l_, x_l);
  if (factorisation_ != Factorisation::Lower) STICTION_PETSC(MatMult(B1_, x_l, work_a_));
  STICTION_PETSC(VecRestoreSubVector(x, is_l_, &x_l));
  if (factorisation_ == Factorisation::Lower) {  // x_a = y
    Vec x_a;
    STICTION_PETSC(VecGetSubVector(work_, is_a_, &y_a));
    STICTION_PETSC(VecGetSubVector(x, is_a_, &x_a));
    STICTION_PETSC(VecCopy(y_a, x_a));
    STICTION_PETSC(VecRestoreSubVector(x, is_a_, &x_a));
    STICTION_PETSC(VecRestoreSubVector(work_, is_a_, &y_a));
    return;
  }
  // x_a = P_A^-1 (r_a - B1 x_lambda)
  STICTION_PETSC(VecCopy(r, work2_));
  Vec w_a;
  STICTION_PETSC(VecGetSubVector(work2_, is_a_, &w_a));
  STICTION_PETSC(VecAXPY(w_a, -1.0, work_a_));
  STICTION_PETSC(VecRestoreSubVector(work2_, is_a_, &w_a));
  inner_->apply(work2_, x);
}

}  // namespace stiction::solvers
