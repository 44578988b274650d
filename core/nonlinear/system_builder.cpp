#include "nonlinear/system_builder.hpp"

#include <algorithm>
#include <cmath>

#include "fem/elasticity_assembly.hpp"
#include "nonlinear/augmented_matrix.hpp"

namespace stiction::nonlinear {

MatNullSpace rigid_body_modes(const fem::DofLayout& layout, const fem::FieldSpace& space) {
  const MPI_Comm comm = layout.comm();
  const int n_extra = static_cast<int>(layout.n_total()) - space.n_dofs();
  const int d = space.dim();
  const mesh::Mesh& m = space.mesh();
  double c[3] = {0, 0, 0};  // rotate about the centroid: better-conditioned modes
  for (int v = 0; v < m.n_vertices(); ++v)
    for (int k = 0; k < d; ++k) c[k] += m.vertex(v)[k] / m.n_vertices();
  const int n_modes = d == 2 ? 3 : 6;
  std::vector<std::vector<double>> modes(n_modes);
  for (int mode = 0; mode < n_modes; ++mode) {
    space.interpolate(
        [&](const double* X, double* out) {
          const double x = X[0] - c[0], y = X[1] - c[1], z = d == 3 ? X[2] - c[2] : 0.0;
          std::fill(out, out + d, 0.0);
          if (mode < d) {
            out[mode] = 1;
          } else if (d == 2) {
            out[0] = -y, out[1] = x;
          } else if (mode == 3) {
            out[1] = -z, out[2] = y;
          } else if (mode == 4) {
            out[0] = z, out[2] = -x;
          } else {
            out[0] = -y, out[1] = x;
          }
        },
        modes[mode]);
  }
  // Modified Gram-Schmidt: MatNullSpaceCreate requires orthonormal vectors.
  for (int i = 0; i < n_modes; ++i) {
    for (int j = 0; j < i; ++j) {
      double dot = 0;
      for (size_t k = 0; k < modes[i].size(); ++k) dot += modes[i][k] * modes[j][k];
      for (size_t k = 0; k < modes[i].size(); ++k) modes[i][k] -= dot * modes[j][k];
    }
    double nrm = 0;
    for (double v : modes[i]) nrm += v * v;
    nrm = std::sqrt(nrm);
    for (double& v : modes[i]) v /= nrm;
  }
  std::vector<Vec> vecs(n_modes);
  const bool blocked = !space.has_pressure() && n_extra % d == 0 && layout.n_owned() % d == 0;
  for (int i = 0; i < n_modes; ++i) {
    modes[i].resize(layout.n_total(), 0.0);
    vecs[i] = layout.create_vector();
    STICTION_PETSC(VecSetBlockSize(vecs[i], blocked ? d : 1));
    layout.scatter(modes[i], vecs[i]);
  }
  MatNullSpace nsp;
  STICTION_PETSC(MatNullSpaceCreate(comm, PETSC_FALSE, n_modes, vecs.data(), &nsp));
  for (Vec& v : vecs) VecDestroy(&v);
  return nsp;
}

NewtonSystemBuilder::NewtonSystemBuilder(const fem::DofLayout& layout, const ElasticityProblem& problem,
                                         PetscInt n_multipliers)
    : layout_(layout), problem_(problem) {
  const fem::FieldSpace& space = *problem.space;
  const MPI_Comm comm = layout.comm();
  if (layout.n_total() != space.n_dofs() + n_multipliers)
    throw Error("system builder: the layout does not number this system", ErrorKind::Internal);
  system_.comm = comm;
  system_.block_size = space.has_pressure() ? 1 : space.dim();
  stiffness_ = std::make_unique<fem::StiffnessMatrix>(layout, space);
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(stiffness_->mat())));
  *system_.matrix.out() = stiffness_->mat();  // replaced by the augmented matrix with contact
  const PetscInt n_total = layout.n_total();
  *system_.rhs.out() = layout.create_vector();
  add_field("u_l", space.linear_block(), space.dim());
  if (fem::is_quadratic(space.kind())) add_field("u_q", space.quadratic_block(), space.dim());
  if (space.has_pressure()) add_field("p", space.pressure_block(), 1);
  if (n_multipliers > 0) add_field("lambda", {space.n_dofs(), static_cast<int>(n_total)}, space.dim());
  if (space.has_pressure()) {
    *system_.pressure_mass.out() = fem::assemble_pressure_mass(layout, space);
    // The moduli of the (first) mixed law; the paper's scenes have one rubber body.
    for (const auto* m : problem.cell_material)
      if (m->mixed_bulk_modulus() > 0) {
        system_.mixed_shear_modulus = m->mixed_shear_modulus();
        system_.mixed_bulk_modulus = m->mixed_bulk_modulus();
        break;
      }
  }
  *system_.near_null_space.out() = rigid_body_modes(layout, space);
  STICTION_PETSC(MatSetNearNullSpace(system_.matrix, system_.near_null_space));
}

void NewtonSystemBuilder::add_field(const char* name, std::pair<int, int> range, int block_size) {
  FieldBlock f{name, {}, block_size};
  if (layout_.identity()) {
    STICTION_PETSC(ISCreateStride(system_.comm, range.second - range.first, range.first, 1, f.is.out()));
  } else {
    const std::vector<PetscInt> owned = layout_.owned_indices(range.first, range.second);
    STICTION_PETSC(ISCreateGeneral(system_.comm, static_cast<PetscInt>(owned.size()), owned.data(), PETSC_COPY_VALUES,
                                   f.is.out()));
  }
  STICTION_PETSC(ISSetBlockSize(f.is, block_size));
  system_.fields.push_back(std::move(f));
}

void NewtonSystemBuilder::assemble(double t, fem::StateView u, const std::vector<double>& lambda, fem::StateView r_u,
                                   const std::vector<double>& r_c, const ConstraintSet& constraints,
                                   const DirichletLifting& lifting, bool lift, fem::ResidualView force_scratch) {
  if (!constraints.empty()) system_.matrix.reset();  // the caller released the backend's set-up on it
  stiffness_->begin_assembly();
  fem::assemble_internal(*problem_.space, problem_.cell_material, u, {}, stiffness_.get(),
                         &layout_.row_cells());
  stiffness_->end_assembly();
  if (!constraints.empty()) border_with_constraints(t, u, lambda, force_scratch, constraints);
  // The right side -r on the owned rows: displacement (and pressure) rows, then multipliers.
  const PetscInt n_u = problem_.space->n_dofs();
  PetscScalar* b;
  STICTION_PETSC(VecGetArray(system_.rhs, &b));
  for (PetscInt j = 0; j < layout_.n_owned(); ++j) {
    const PetscInt a = layout_.local_of_owned(j);
    b[j] = a < n_u ? -r_u[a] : -r_c[a - n_u];
  }
  STICTION_PETSC(VecRestoreArray(system_.rhs, &b));
  lifting.apply(layout_, system_.matrix, system_.rhs, u, lift);
}

// The augmented matrix (30): the tangent bordered by -B^T, C_u and C_lambda, and the
// multiplier surface the contact preconditioner reads.
void NewtonSystemBuilder::border_with_constraints(double t, fem::StateView u, const std::vector<double>& lambda,
                                                  fem::ResidualView force_scratch,
                                                  const ConstraintSet& constraints) {
  const PetscInt n_u = problem_.space->n_dofs(), m = constraints.n_multipliers();
  SparseEntries blocks;
  std::vector<double> scratch_c;
  constraints.evaluate(t, u, lambda, force_scratch, scratch_c, &blocks, n_u);
  if (stiffness_->distributed()) {
    *system_.matrix.out() =
        build_distributed_augmented_matrix(stiffness_->mat(), layout_, n_u, blocks, stiffness_->block_size());
    stiffness_->release();  // its rows are in the augmented matrix now
  } else
    *system_.matrix.out() = build_augmented_matrix(system_.comm, stiffness_->take_arrays(), m, blocks,
                                                   stiffness_->block_size());
  STICTION_PETSC(MatSetNearNullSpace(system_.matrix, system_.near_null_space));
  const MultiplierSurfaceEntries surface = constraints.describe_surface();
  MultiplierSurface& to = system_.multiplier_surface;
  *to.mass.out() = build_block_matrix(layout_, n_u, m, surface.mass, Diagonal::Omit);
  *to.laplacian.out() = build_block_matrix(layout_, n_u, m, surface.laplacian, Diagonal::Omit);
  *to.projector.out() = build_block_matrix(layout_, n_u, m, surface.projector, Diagonal::Omit);
  *to.constrained.out() = build_block_matrix(layout_, n_u, m, surface.constrained, Diagonal::Omit);
  *to.slip_rows.out() = build_block_matrix(layout_, n_u, m, surface.slip_rows, Diagonal::Omit);
}

}  // namespace stiction::nonlinear
