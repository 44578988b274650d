#include "mixed_pc.hpp"

#include "block_view.hpp"
#include "solver_figures.hpp"

#include "common/error.hpp"

namespace stiction::solvers {

MixedPreconditioner::MixedPreconditioner(MPI_Comm comm, const std::string& prefix,
                                         const HierarchicalPreconditioner& hp)
    : hp_(hp), prefix_(prefix) {
  STICTION_PETSC(KSPCreate(comm, ksp_pp_.out()));
  STICTION_PETSC(KSPSetOptionsPrefix(ksp_pp_, (prefix + "pp_").c_str()));
}

double MixedPreconditioner::pressure_schur_scale(double shear_modulus, double bulk_modulus) {
  return -(1 / shear_modulus + 1 / bulk_modulus);
}

void MixedPreconditioner::setup(Mat A, IS displacement, IS pressure, Mat pressure_mass, double shear_modulus,
                                double bulk_modulus) {
  if (!pressure_mass || !(shear_modulus > 0) || !(bulk_modulus > 0))
    throw Error("MHP (11) needs the pressure mass matrix and the moduli of a mixed law", ErrorKind::Internal);
  const double alpha = pressure_schur_scale(shear_modulus, bulk_modulus);
  form_ = schur_form_from_options(prefix_, "mhp_fact", {"upper", SchurForm::Upper}, {"full", SchurForm::Full}, form_);
  if (!is_u_) {
    STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(pressure)));
    *is_p_.out() = pressure;
    STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(displacement)));
    *is_u_.out() = displacement;
  }
  const bool first_setup = !S_;
  // The couplings are only multiplied: views of A where its blocks allow, else copies.
  const IndexRange u = contiguous_range(displacement), p = contiguous_range(pressure);
  if (block_views_possible(A, {u, p}) && !block_copies_requested(prefix_)) {
    *A_up_.out() = block_view(A, u, p);
    *A_pu_.out() = block_view(A, p, u);
  } else {
    const MatReuse reuse = A_up_ && pattern_ == pattern_key(A) ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX;
    pattern_ = pattern_key(A);
    Mat up = A_up_, pu = A_pu_;
    STICTION_PETSC(MatCreateSubMatrix(A, is_u_, is_p_, reuse, &up));
    STICTION_PETSC(MatCreateSubMatrix(A, is_p_, is_u_, reuse, &pu));
    if (reuse == MAT_INITIAL_MATRIX) {
      *A_up_.out() = up;
      *A_pu_.out() = pu;
    }
  }
  if (first_setup) {
    // S~ = alpha M_p is constant: built once.
    STICTION_PETSC(MatDuplicate(pressure_mass, MAT_COPY_VALUES, S_.out()));
    STICTION_PETSC(MatScale(S_, alpha));
    STICTION_PETSC(KSPSetOperators(ksp_pp_, S_, S_));
    STICTION_PETSC(KSPSetFromOptions(ksp_pp_));
    STICTION_PETSC(KSPSetUp(ksp_pp_));
    STICTION_PETSC(MatCreateVecs(A, work_.out(), work2_.out()));
    STICTION_PETSC(MatCreateVecs(S_, work_p_.out(), nullptr));
    STICTION_PETSC(MatCreateVecs(A_up_, nullptr, work_u_.out()));
  }
}

double MixedPreconditioner::copied_blocks_mb() const {
  return aij_storage_mb(A_up_) + aij_storage_mb(A_pu_) + aij_storage_mb(S_);
}

void MixedPreconditioner::release() {
  A_up_.reset(), A_pu_.reset();  // S~ = alpha M_p and its solver stay: they do not change
  pattern_ = {};
}

void MixedPreconditioner::set_pressure_operator(Mat S) {
  STICTION_PETSC(KSPSetOperators(ksp_pp_, S, S));
  STICTION_PETSC(KSPSetUp(ksp_pp_));
}

void MixedPreconditioner::apply(Vec r, Vec x) const {
  Vec rp, xp, wu;
  STICTION_PETSC(VecGetSubVector(r, is_p_, &rp));
  STICTION_PETSC(VecCopy(r, work_));
  if (form_ == SchurForm::Full) {
    hp_.apply(r, work2_);                                // y_u = HP r_u
    Vec yu;
    STICTION_PETSC(VecGetSubVector(work2_, is_u_, &yu));
    STICTION_PETSC(MatMult(A_pu_, yu, work_p_));
    STICTION_PETSC(VecRestoreSubVector(work2_, is_u_, &yu));
    STICTION_PETSC(VecAYPX(work_p_, -1.0, rp));          // r_p - Bp y_u
    STICTION_PETSC(VecGetSubVector(x, is_p_, &xp));
    STICTION_PETSC(KSPSolve(ksp_pp_, work_p_, xp));      // x_p = S~^-1 (...)
  } else {
    STICTION_PETSC(VecGetSubVector(x, is_p_, &xp));
    STICTION_PETSC(KSPSolve(ksp_pp_, rp, xp));           // y_p = S~^-1 r_p
  }
  STICTION_PETSC(VecGetSubVector(work_, is_u_, &wu));
  STICTION_PETSC(MatMult(A_up_, xp, work_u_));
  STICTION_PETSC(VecAXPY(wu, -1.0, work_u_));            // r_u - Bp^T x_p
  STICTION_PETSC(VecRestoreSubVector(work_, is_u_, &wu));
  STICTION_PETSC(VecRestoreSubVector(x, is_p_, &xp));
  STICTION_PETSC(VecRestoreSubVector(r, is_p_, &rp));
  hp_.apply(work_, x);                                   // x_u = HP (...); x_p kept
}

}  // namespace stiction::solvers
