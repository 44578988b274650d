#pragma once
// The slave side of a contact pair (paper Sec. 4.1): its facets, the multiplier nodes (the
// facets' vertices: lambda is continuous P1 on the slave surface, Cartesian components),
// and the integrals that do not change with the motion because they are taken over the
// reference slave surface:
//
//   B_int[i, a] = int phi_i N_a      (P1 multiplier hat phi_i, displacement shape N_a)
//   m_i         = int phi_i          (lumped multiplier mass)
//   M[i, j]     = int phi_i phi_j    (consistent multiplier mass, for the Schur level (32))
//   K[i, j]     = int grad_s phi_i . grad_s phi_j  (surface Laplacian, for the fractional
//                 Schur model of the contact preconditioner)
//
// Choice (the paper integrates over the current surface without saying so): integrating over
// the reference slave surface makes the weighted gaps exact linear functions of the slave
// displacement, so the constraint rows of (30) are the exact derivatives of (13)-(19).
#include <array>
#include <vector>

#include "fem/field_space.hpp"

namespace stiction::contact {

struct SlaveSurface {
  int dim = 0;
  std::vector<int> vertices;  // mesh vertex of multiplier node i
  // B_int in compressed rows: row i holds (displacement node, coefficient) pairs.
  std::vector<int> b_start, b_node;
  std::vector<double> b_coef;
  std::vector<double> lumped_mass;  // m_i
  std::vector<std::array<double, 3>> reference_position;  // X of each multiplier node
  // Consistent mass M (symmetric) as (i, j, value) entries, duplicates summed by the user.
  std::vector<int> mass_i, mass_j;
  std::vector<double> mass_v;
  // Surface stiffness K (symmetric), entries as for M.
  std::vector<int> stiffness_i, stiffness_j;
  std::vector<double> stiffness_v;
  // First moments int phi_i X (dim entries per node): reference positions weighted like gaps.
  std::vector<double> first_moment;
  double diameter = 0;  // bounding-box diagonal of the slave surface

  int n_nodes() const { return static_cast<int>(vertices.size()); }
  // Characteristic facet size at node i: m_i^(1/(dim-1)).
  double local_size(int i) const;
};

// The slave surface of the facets tagged `facet_tag`; throws when the tag has no facets.
SlaveSurface make_slave_surface(const fem::FieldSpace& space, int facet_tag, const std::string& name);

}  // namespace stiction::contact
