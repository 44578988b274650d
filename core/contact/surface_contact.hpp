#pragma once
// Frictional contact of a slave surface against a deformable master surface (paper Sec. 4.1):
// two bodies, or self-contact when both surfaces belong to one body; in 2D (plane strain,
// P1/P2 segments) and 3D (P1/P2 triangles).
//
// Kinematics (current configuration x = X + u):
//   * 2D: every slave quadrature point x1 is projected on the master surface by the closest
//     point x2 = x2(eta) of a master facet (Newton on (x1 - x2(eta)) . x2'(eta) = 0, clamped
//     to the facet's ends: facet_projection.hpp). Where a point projects into the interior
//     of two master facets sharing a vertex (the concave side of that vertex), the contact
//     point blends both projections so that it moves continuously (contact_point in the .cpp).
//   * 3D (choice, where the issue asks for the closest point): x2 is where the line through
//     x1 along the slave facet's normal n1(xi) crosses a master triangle (Newton on
//     x1 + t n1 - x2(eta) = 0). The closest point jumps from one triangle to the next on
//     the concave side of a master edge, where every penetrated point of a convex master
//     lies; measured on hertz-spheres-3d level 0 with lu-mumps, Newton then wandered for 25
//     iterations in the first load step (residual 1e-2 to 1, up to 47 state changes per
//     iteration), also with the load step cut by four. The normal's crossing moves
//     continuously across master edges: 5 + 5 iterations there (5 + 7 at level 1).
//     (The 2D blend would need weights over every triangle around an edge or vertex.)
//     [[contact]] master_point = "closest" selects the paper's closest point in 3D too
//     (Newton inside a master triangle, then along its edges, clamped at its vertices:
//     facet_projection.hpp), with the exact Jacobian wherever the closest point stays on
//     one face of one triangle. On a flat master both rules converge alike and their
//     contact forces differ by 1.7e-5 (tests/verification/test_master_point.cpp); on
//     hertz-spheres-3d with the key set, level 0, lu-mumps stops at step 1 after 25
//     iterations (26 state changes in the last) and schur-amg breaks down after 9.
//   * candidates: a Boost.Geometry R-tree over the boxes of the master facets' control nets
//     (which hold a curved facet), rebuilt at every evaluation without derivatives; in 3D
//     the facets whose boxes meet the slave normal's segment within the search radius (the
//     closest-point rule: the nearest boxes in order), each first tested against the line
//     (facets::line_may_cross) before the crossing's Newton. The Jacobian at that iterate
//     rebuilds the master points the evaluation found instead of searching again (found_
//     below). A point whose master point is farther than the search radius, off the facet,
//     or on the master's back does not contribute.
//   * integration (choice). 2D, segments (mortar-style): each slave facet is cut where the
//     projections of the master facet's end points land, and each piece is integrated with
//     its own Gauss rule, so the integrands are smooth on every piece and B_ext is exact
//     for flat surfaces (the non-matching patch test passes to round-off). 3D: cutting a
//     slave triangle by the projected master triangles is polygon clipping on a curved
//     surface; instead each slave triangle is split into four and each part integrated with
//     a degree-4 rule (36 points), so B_ext carries a quadrature error where master edges
//     cross a slave facet (non-matching 3D meshes pass a patch test only to that error).
//   * per slave node i:  G_i = int phi_i (x1 - x2),
//                        S_i = int phi_i [(x1 - x1^p) - (x2 - x2^p)]     (15)-(16)
//     x1^p, x2^p the previous-step positions of the same material points, integrals over
//     the reference slave surface (as in slave_surface.hpp);
//     n_i = -m_i / |m_i|, m_i = int phi_i n1 ds the lumped L2 projection of the slave's
//     outward normal in the current configuration (so n_i points from master to slave).
//   * forces: the slave carries +lambda and the master -lambda at the projected points:
//     r_u -= B_int^T lambda - B_ext^T lambda, both integrated on the same segments.
// Linearisation: exact, including the variation of the nodal normals, of the master point's
// parameter eta (implicit function theorem on the projection or crossing equation) and of
// B_ext. The moving ends of the 2D segments are not differentiated: every integrand is
// continuous across them, so they add no term to the exact integral, and none to the Gauss
// sums when the integrands are polynomial (P1; checked against finite differences in
// tests/unit/contact, 2D and 3D). At P2 they add a term of the size of the Gauss rule's
// error: computed (d xi / du of each cut exact, the pieces' sums differentiated along xi),
// it changed the Jacobian by 6e-11 of its largest entry on a curved P2 master and left
// the frictional ironing's Newton iterations unchanged, so it is left out. In 3D the
// residual is only C0 where a crossing passes a master edge (B_ext's shape
// functions have a kink there): Newton still converged quadratically on hertz-spheres-3d.
#include <string>
#include <vector>

#include "contact/contact_pair.hpp"
#include "contact/facet_projection.hpp"
#include "fem/app_view.hpp"

namespace stiction::contact {

class SurfaceContact final : public ContactPair {
public:
  // search_radius <= 0: twice the longest master facet.
  SurfaceContact(std::string name, const fem::FieldSpace& space, int slave_tag, int master_tag,
                 ContactSettings settings, double search_radius);

  std::vector<std::pair<std::string, int>> surfaces() const override {
    return {{"slave", slave_tag_}, {"master", master_tag_}};
  }
  // The same pair over a finer space: a requested radius is kept, a default one is derived
  // again from the finer space's master facets.
  std::unique_ptr<nonlinear::MultiplierConstraint> over(const fem::FieldSpace& space) const override {
    return std::make_unique<SurfaceContact>(name(), space, slave_tag_, master_tag_, settings_, requested_search_radius_);
  }
  double search_radius() const { return search_radius_; }

private:
  void compute_kinematics(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u,
                          nonlinear::SparseEntries* jacobian, PetscInt offset, bool with_derivatives,
                          std::vector<NodeKinematics>& nodes) const override;
  template <int D>
  void kinematics(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u,
                  nonlinear::SparseEntries* jacobian, PetscInt offset, bool with_derivatives,
                  std::vector<NodeKinematics>& nodes) const;
  // Distributed, a process integrates the facets holding one of its slave nodes (every
  // integral of those nodes) and adds the forces of the facets whose first node it owns
  // (each facet's forces once).
  bool evaluated_here(const SurfaceFacet& f) const;
  bool adds_forces(const SurfaceFacet& f) const;
  template <int D>
  // n_i of every slave node this process evaluates; dn_i where derive[i].
  void nodal_normals(fem::StateView u, const std::vector<char>& derive,
                     std::vector<NodeKinematics>& nodes) const;

  const fem::FieldSpace& space_;
  std::vector<SurfaceFacet> slave_facets_, master_facets_;
  int master_tag_;
  double requested_search_radius_;  // as given: <= 0 derives it from the space's master facets
  double search_radius_;

  // What the last evaluation without derivatives found (at ContactPair's last evaluated
  // point): per slave facet its integration points, per point the master points it chose.
  // The Jacobian at that iterate rebuilds them (facets::projection_at) instead of searching
  // the master again, which was half of its time. A few dozen bytes per point.
  struct FoundPoint {
    double eta[2], weight;
    int first_branch, n_branches;
  };
  struct FoundBranch {
    int facet;
    bool crossing;
    int face;
    double eta[2], t;
  };
  struct SearchRecord {
    bool valid = false;
    std::vector<int> facet_points;  // slave facet k's points: [facet_points[k], facet_points[k + 1])
    std::vector<char> searched;      // slave facet k had master candidates
    std::vector<FoundPoint> points;
    std::vector<FoundBranch> branches;
  };
  mutable SearchRecord found_;
};

}  // namespace stiction::contact
