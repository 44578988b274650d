#pragma once
// Assembly of the hyperelastic residual and consistent tangent (paper (1), total Lagrangian):
//   R_a = int_Omega P(F) . grad_X N_a  -  int_Omega f N_a  -  int_Gamma_N t N_a
//   K_ab(i,k) = int_Omega A_iJkL dN_a/dX_J dN_b/dX_L
// The internal part loops over cells with a kernel specialised for the dimension and the
// number of shape functions; loads are dead loads on the reference configuration.
#include <array>
#include <limits>
#include <vector>

#include "fem/app_view.hpp"
#include "fem/dof_layout.hpp"
#include "fem/field_space.hpp"
#include "fem/stiffness_matrix.hpp"
#include "materials/material.hpp"

namespace stiction::fem {

struct InternalForceStatus {
  int inverted_cell = -1;  // first cell with det F <= 0 at a quadrature point (finite-strain law), or -1
  // First quadratic cell valid at its quadrature points but with det F <= 0 at one of its
  // nodes (its boundary curves back on itself), or -1: the energy is defined, the
  // configuration is not a valid one.
  int folded_cell = -1;
  // Smallest det F at the quadrature points and (quadratic cells) the nodes of the cells whose
  // law needs det F > 0; +inf without such cells. How close a state is to folding: a cell
  // crushed at the edge of a contact zone shows here long before it folds.
  double min_det_f = std::numeric_limits<double>::infinity();
  int min_det_f_cell = -1;  // where it is
};

// Adds the internal force vector (residual may be empty: no residual) and the tangent
// (tangent may be null; values are added between its begin_assembly and end_assembly, which
// the caller calls) for the coefficient vector u.
// cell_material[c] is the law of cell c. With cells, only those cells (a rank's share of
// the mesh, fem::MeshPartition) are assembled; the status names the first of them that fails.
InternalForceStatus assemble_internal(const FieldSpace& space,
                                      const std::vector<const materials::Material*>& cell_material,
                                      StateView u, ResidualView residual,
                                      StiffnessMatrix* tangent, const std::vector<int>* cells = nullptr);

// residual -= int_Omega f N_a (f may vary in space).
void subtract_body_force(const FieldSpace& space, const VectorField& f, ResidualView residual);
// residual -= int_{facets with tag} t N_a.
void subtract_traction(const FieldSpace& space, int facet_tag, const VectorField& t,
                       ResidualView residual);

// P1 mass matrix of the pressure field, M_p[i][j] = int q_i q_j over mixed cells, in the
// pressure block's numbering (DofLayout::block_numbering; on one rank, row i = pressure
// dof - first pressure dof). Each rank adds its own cells; the rows go to their owners.
Mat assemble_pressure_mass(const DofLayout& layout, const FieldSpace& space);

// Cauchy stress (3x3, row-major) at each cell's centroid, for output: of every cell, or of
// the given cells in their order (u need hold only their nodes).
std::vector<double> cell_cauchy_stress(const FieldSpace& space,
                                       const std::vector<const materials::Material*>& cell_material,
                                       StateView u, const std::vector<int>* cells = nullptr);

// Integral of the first Piola traction P N over the boundary facets tagged `facet_tag`
// (reference configuration, N the facet's outward normal): the force the body's material
// transmits through that surface (the paper's F1 on a Dirichlet boundary, F4 / -F5 on the
// slave / master contact surfaces). 3 components (the third is 0 in 2D). With a layout,
// only the facets whose lowest vertex this process owns (their cells reach its owned rows,
// so u holds their nodes); the caller sums over processes.
std::array<double, 3> boundary_force(const FieldSpace& space, const std::vector<const materials::Material*>& cell_material,
                                     StateView u, int facet_tag, const DofLayout* layout = nullptr);

}  // namespace stiction::fem
