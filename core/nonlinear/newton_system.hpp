#pragma once
// One Newton system as the linear-solver backends see it: the matrix (block size = dim for
// the displacement field), the right side, named field index sets (u_l, u_q; later p,
// lambda) so a backend can split it, and the rigid-body near-null space of the
// displacement field. The same object is recorded and replayed.
#include <string>
#include <vector>

#include "common/petsc.hpp"

namespace stiction::nonlinear {

struct FieldBlock {
  std::string name;  // "u_l", "u_q", ...
  PetscIS is;        // global indices of the block
  int block_size = 1;
};

// The matrices of MultiplierSurfaceEntries (multiplier_constraint.hpp).
struct MultiplierSurface {
  PetscMat mass, laplacian, projector, constrained, slip_rows;
};

struct NewtonSystem {
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscMat matrix;
  PetscVec rhs;
  std::vector<FieldBlock> fields;
  PetscNullSpace near_null_space;  // rigid-body modes of the displacement (also on matrix)
  int block_size = 1;
  // Mixed (u-p) systems only: the P1 pressure mass matrix M_p (on the p block's numbering)
  // and the moduli of the mixed law, from which MHP (11) approximates S_p.
  PetscMat pressure_mass;
  double mixed_shear_modulus = 0, mixed_bulk_modulus = 0;
  // Contact systems only: the multiplier surface (MultiplierSurfaceEntries) on the lambda
  // block's numbering, from which the contact preconditioner forms its Schur approximation.
  MultiplierSurface multiplier_surface;

  const FieldBlock* field(const std::string& name) const {
    for (const auto& f : fields)
      if (f.name == name) return &f;
    return nullptr;
  }
};

}  // namespace stiction::nonlinear
