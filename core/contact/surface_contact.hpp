#pragma once
// Frictional contact of a slave surface against a deformable master surface (paper Sec. 4.1):
// two bodies, or self-contact when both surfaces belong to one body. Plane strain (2D) for
// now: the constructor refuses a 3D mesh with a clear message.
//
// Kinematics (current configuration x = X + u):
//   * every slave quadrature point x1 is projected on the master surface by the closest
//     point x2 = x2(eta) of a master facet (Newton on (x1 - x2(eta)) . x2'(eta) = 0);
//     candidate facets come from a Boost.Geometry R-tree over the master facets' bounding
//     boxes, rebuilt at every evaluation. A point whose projection is farther than the
//     search radius, falls off the facet, or sees the master's back does not contribute.
//     Where a point projects into the interior of two master facets sharing a vertex (the
//     concave side of that vertex), the contact point blends both projections so that it
//     moves continuously (see contact_point in the .cpp).
//   * segments (mortar-style integration, choice): each slave facet is cut where the
//     projections of the master facet's end points land, and each piece is integrated with
//     its own Gauss rule, so the integrands are smooth on every piece and B_ext is exact
//     for flat surfaces (the non-matching patch test passes to round-off).
//   * per slave node i:  G_i = int phi_i (x1 - x2),
//                        S_i = int phi_i [(x1 - x1^p) - (x2 - x2^p)]     (15)-(16)
//     x1^p, x2^p the previous-step positions of the same material points, integrals over
//     the reference slave surface (as in slave_surface.hpp);
//     n_i = -m_i / |m_i|, m_i = int phi_i n1 ds the lumped L2 projection of the slave's
//     outward normal in the current configuration (so n_i points from master to slave).
//   * forces: the slave carries +lambda and the master -lambda at the projected points:
//     r_u -= B_int^T lambda - B_ext^T lambda, both integrated on the same segments.
// Linearisation: exact, including the variation of the nodal normals, of the projection
// parameter eta (implicit function theorem on the projection equation) and of B_ext; the
// moving ends of the segments add no term because every integrand is continuous across
// them (checked against finite differences in tests/unit/contact).
#include <string>
#include <vector>

#include "contact/contact_pair.hpp"

namespace stiction::contact {

class SurfaceContact final : public ContactPair {
public:
  // search_radius <= 0: twice the longest master facet.
  SurfaceContact(std::string name, const fem::FieldSpace& space, int slave_tag, int master_tag,
                 ContactSettings settings, double search_radius);

  // One facet of either surface: its P2 (or P1) nodes, reference geometry X0 + xi E, and
  // the sign making sign * (E_y, -E_x) its outward normal.
  struct Facet {
    int vertex[2] = {0, 0};
    std::vector<int> nodes;
    double X0[2] = {0, 0}, E[2] = {0, 0};
    double outward = 1;
    int node_of_vertex[2] = {-1, -1};  // slave facets: multiplier node of each vertex
  };

  std::vector<std::pair<std::string, int>> surfaces() const override {
    return {{"slave", slave_tag_}, {"master", master_tag_}};
  }

private:
  void compute_kinematics(int step, const std::vector<double>& u, const double* lambda, std::vector<double>* r_u,
                          nonlinear::SparseEntries* jacobian, PetscInt offset, bool with_derivatives,
                          std::vector<NodeKinematics>& nodes) const override;
  void nodal_normals(const std::vector<double>& u, bool with_derivatives, std::vector<NodeKinematics>& nodes) const;

  const fem::FieldSpace& space_;
  std::vector<Facet> slave_facets_, master_facets_;
  int master_tag_;
  double search_radius_;
};

}  // namespace stiction::contact
