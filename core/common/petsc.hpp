#pragma once
// Move-only RAII owners for PETSc handles (style.md habit 4) and an error check that turns a
// PETSc error code into a stiction::Error carrying PETSc's own message.
#include <petscksp.h>

#include <string>
#include <utility>

#include "common/error.hpp"

namespace stiction {

void petsc_check(PetscErrorCode ierr, const char* expr, const char* file, int line);

#define STICTION_PETSC(expr) ::stiction::petsc_check((expr), #expr, __FILE__, __LINE__)

template <class Handle, PetscErrorCode (*Destroy)(Handle*)>
class PetscOwner {
public:
  PetscOwner() = default;
  explicit PetscOwner(Handle h) : h_(h) {}
  PetscOwner(const PetscOwner&) = delete;
  PetscOwner& operator=(const PetscOwner&) = delete;
  PetscOwner(PetscOwner&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  PetscOwner& operator=(PetscOwner&& o) noexcept {
    if (this != &o) {
      reset();
      h_ = std::exchange(o.h_, nullptr);
    }
    return *this;
  }
  ~PetscOwner() { reset(); }

  void reset() {
    if (h_) Destroy(&h_);
    h_ = nullptr;
  }
  Handle get() const { return h_; }
  Handle* out() {  // for PETSc's XxxCreate(..., &h)
    reset();
    return &h_;
  }
  operator Handle() const { return h_; }
  explicit operator bool() const { return h_ != nullptr; }

private:
  Handle h_ = nullptr;
};

using PetscMat = PetscOwner<Mat, MatDestroy>;
using PetscVec = PetscOwner<Vec, VecDestroy>;
using PetscIS = PetscOwner<IS, ISDestroy>;
using PetscKSP = PetscOwner<KSP, KSPDestroy>;
using PetscNullSpace = PetscOwner<MatNullSpace, MatNullSpaceDestroy>;

// Initialises PETSc once for the process (argc/argv may be empty) and finalises at exit.
// PETSc errors are returned, not printed: petsc_check turns them into stiction::Error.
class PetscSession {
public:
  PetscSession(int* argc, char*** argv);
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;
};

std::string petsc_version_string();

// Identity of a matrix's nonzero pattern: the object (PETSc never reuses an object id) and
// its nonzero state (bumped whenever the pattern changes). Sub-matrices may be extracted
// with MAT_REUSE_MATRIX only while this key is unchanged: a contact system is rebuilt with
// a new pattern whenever the projections or the active set move.
struct PatternKey {
  PetscInt64 id = -1;
  PetscObjectState state = -1;
  bool operator==(const PatternKey&) const = default;
};
PatternKey pattern_key(Mat A);

}  // namespace stiction
