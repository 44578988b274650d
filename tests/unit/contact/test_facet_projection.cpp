// The closest point of a point on a 3D master triangle (facet_projection.hpp): exact
// distances on a flat triangle (interior, edge, vertex), and d eta / dx of a curved P2
// triangle against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "contact/facet_projection.hpp"

namespace stiction::contact {
namespace {

using Vec = facets::Geometry<3>::Vec;
using Param = facets::Geometry<3>::Param;

// The reference triangle (0,0,0), (1,0,0), (0,1,0) with n_nodes nodes (3: P1, 6: P2); the
// tests pass their displacements (n_nodes x 3) to the evaluator.
SurfaceFacet unit_triangle(int n_nodes) {
  SurfaceFacet f;
  f.n_vertices = 3;
  for (int k = 0; k < 3; ++k) f.vertex[k] = k;
  for (int a = 0; a < n_nodes; ++a) f.nodes.push_back(a);
  f.E[0][0] = 1, f.E[1][1] = 1;
  return f;
}

TEST(FacetProjection, ClosestPointOnAFlatTriangle) {
  const facets::FacetEvaluator<3> ev(fem::BasisKind::P1, 3);
  const SurfaceFacet f = unit_triangle(3);
  const std::vector<double> u(9, 0.0);
  struct Case {
    Vec x;
    Param eta;
    double distance;
    bool interior;
  };
  const Case cases[] = {
      {Vec(0.2, 0.3, 0.5), Param(0.2, 0.3), 0.5, true},                 // above the interior
      {Vec(0.6, 0.6, 0.1), Param(0.5, 0.5), std::sqrt(0.03), false},    // beyond the hypotenuse
      {Vec(0.4, -0.2, -0.3), Param(0.4, 0.0), std::sqrt(0.13), false},  // beyond the edge y = 0
      {Vec(-0.3, -0.2, 0.4), Param(0.0, 0.0), std::sqrt(0.29), false},  // beyond vertex 0
      {Vec(1.5, -0.5, 0.0), Param(1.0, 0.0), std::sqrt(0.5), false},    // beyond vertex 1
  };
  for (const Case& c : cases) {
    const auto p = facets::project(ev, f, c.x, u);
    ASSERT_TRUE(p.found) << c.x.transpose();
    EXPECT_FALSE(p.crossing);
    EXPECT_EQ(p.interior, c.interior) << c.x.transpose();
    EXPECT_NEAR((p.eta - c.eta).norm(), 0, 1e-12) << c.x.transpose();
    EXPECT_NEAR(p.distance, c.distance, 1e-12) << c.x.transpose();
  }
  // At a vertex eta does not move.
  EXPECT_TRUE(facets::project(ev, f, cases[3].x, u).sensitivity.isZero(0));
}

// d eta / dx = sensitivity * dF/dx, dF_k / dx_c = y_,k[c] (F_k = (x - y) . y_,k), against
// central differences (h = 1e-6) to 1e-6 relative, inside a curved P2 triangle and on one
// of its edges (where eta moves along the edge only).
TEST(FacetProjection, ClosestPointSensitivityMatchesFiniteDifferences) {
  const facets::FacetEvaluator<3> ev(fem::BasisKind::P2Nodal, 6);
  const SurfaceFacet f = unit_triangle(6);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> u(18);
  for (double& v : u) v = 0.05 * U(rng);
  for (const Vec& x : {Vec(0.3, 0.25, 0.2), Vec(0.45, -0.3, 0.15)}) {
    const auto p = facets::project(ev, f, x, u);
    ASSERT_TRUE(p.found);
    EXPECT_EQ(p.interior, x[1] > 0);
    for (int c = 0; c < 3; ++c) {
      const double h = 1e-6;
      const Param plus = facets::project(ev, f, x + h * Vec::Unit(c), u).eta;
      const Param minus = facets::project(ev, f, x - h * Vec::Unit(c), u).eta;
      const Param difference = (plus - minus) / (2 * h);
      const Param analytic = p.sensitivity * p.y.dx.row(c).transpose();
      EXPECT_LT((difference - analytic).norm(), 1e-6 * std::max(1.0, analytic.norm()))
          << "x " << x.transpose() << ", component " << c << ": " << difference.transpose() << " vs "
          << analytic.transpose();
    }
  }
}

}  // namespace
}  // namespace stiction::contact
