#include "nonlinear/system_builder.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "fem/elasticity_assembly.hpp"
#include "nonlinear/augmented_matrix.hpp"

namespace stiction::nonlinear {

namespace {

// The mean of the mesh's vertices: over a part, of the whole mesh's (each vertex counted by
// the process that owns it).
std::array<double, 3> vertex_centroid(const fem::DofLayout& layout, const fem::FieldSpace& space) {
  const mesh::Mesh& m = space.mesh();
  const int d = space.dim();
  std::array<double, 3> c = {0, 0, 0};
  if (!layout.over_part()) {
    for (int v = 0; v < m.n_vertices(); ++v)
      for (int k = 0; k < d; ++k) c[k] += m.vertex(v)[k] / m.n_vertices();
    return c;
  }
  std::vector<double> sum(4, 0.0);  // coordinates, then the count
  for (int v = 0; v < m.n_vertices(); ++v)
    if (layout.owns(static_cast<PetscInt>(v) * d)) {
      for (int k = 0; k < d; ++k) sum[k] += m.vertex(v)[k];
      sum[3] += 1;
    }
  fem::sum_over_ranks(layout.comm(), sum);
  for (int k = 0; k < d; ++k) c[k] = sum[k] / sum[3];
  return c;
}

}  // namespace

MatNullSpace rigid_body_modes(const fem::DofLayout& layout, const fem::FieldSpace& space) {
  const MPI_Comm comm = layout.comm();
  const int n_extra = static_cast<int>(layout.n_held()) - space.n_dofs();
  const int d = space.dim();
  const std::array<double, 3> c = vertex_centroid(layout, space);  // rotate about it: better-conditioned modes
  const int n_modes = d == 2 ? 3 : 6;
  // Each mode's owned entries, in PETSc's order (zero on the multipliers).
  const auto n_owned = static_cast<size_t>(layout.n_owned());
  std::vector<std::vector<double>> modes(n_modes, std::vector<double>(n_owned, 0.0));
  std::vector<double> held;
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
        held);
    for (size_t j = 0; j < n_owned; ++j)
      if (const auto l = static_cast<size_t>(layout.local_of_owned(static_cast<PetscInt>(j))); l < held.size())
        modes[mode][j] = held[l];
  }
  // Modified Gram-Schmidt: MatNullSpaceCreate requires orthonormal vectors.
  const auto dot = [&](const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0;
    for (size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
    return layout.identity() ? s : fem::sum_over_ranks(comm, s);
  };
  for (int i = 0; i < n_modes; ++i) {
    for (int j = 0; j < i; ++j) {
      const double ij = dot(modes[i], modes[j]);
      for (size_t k = 0; k < n_owned; ++k) modes[i][k] -= ij * modes[j][k];
    }
    const double nrm = std::sqrt(dot(modes[i], modes[i]));
    for (double& v : modes[i]) v /= nrm;
  }
  std::vector<Vec> vecs(n_modes);
  const bool blocked = !space.has_pressure() && n_extra % d == 0 && layout.n_owned() % d == 0;
  for (int i = 0; i < n_modes; ++i) {
    vecs[i] = layout.create_vector();
    STICTION_PETSC(VecSetBlockSize(vecs[i], blocked ? d : 1));
    PetscScalar* a;
    STICTION_PETSC(VecGetArray(vecs[i], &a));
    std::copy(modes[i].begin(), modes[i].end(), a);
    STICTION_PETSC(VecRestoreArray(vecs[i], &a));
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
  if (layout.n_held() != space.n_dofs() + n_multipliers)
    throw Error("system builder: the layout does not number this system", ErrorKind::Internal);
  system_.comm = comm;
  system_.block_size = space.has_pressure() ? 1 : space.dim();
  stiffness_ = std::make_unique<fem::StiffnessMatrix>(layout, space);
  STICTION_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(stiffness_->mat())));
  *system_.matrix.out() = stiffness_->mat();  // replaced by the augmented matrix with contact
  *system_.rhs.out() = layout.create_vector();
  add_field("u_l", space.linear_block(), space.dim());
  if (fem::is_quadratic(space.kind())) add_field("u_q", space.quadratic_block(), space.dim());
  if (space.has_pressure()) add_field("p", space.pressure_block(), 1);
  // The multipliers follow the space's dofs in the layout's local index (whole or a part's).
  if (n_multipliers > 0) add_field("lambda", {space.n_dofs(), static_cast<int>(layout.n_held())}, space.dim());
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

double NewtonSystemBuilder::assemble(double t, fem::StateView u, const std::vector<double>& lambda,
                                     fem::StateView r_u, const std::vector<double>& r_c,
                                     const ConstraintSet& constraints, const DirichletLifting& lifting, bool lift,
                                     fem::ResidualView force_scratch) {
  if (!constraints.empty()) system_.matrix.reset();  // the caller released the backend's set-up on it
  stiffness_->begin_assembly();
  fem::assemble_internal(*problem_.space, problem_.cell_material, u, {}, stiffness_.get(),
                         &layout_.row_cells());
  stiffness_->end_assembly();
  double constraint_seconds = 0;
  if (!constraints.empty()) {
    const auto t0 = std::chrono::steady_clock::now();
    border_with_constraints(t, u, lambda, force_scratch, constraints);
    constraint_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
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
  return constraint_seconds;
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
