// The closest point of a point on a 3D master triangle (facet_projection.hpp): exact
// distances on a flat triangle (interior, edge, vertex), and d eta / dx of a curved P2
// triangle against central differences. The crossing of a line: the control net (the
// Bernstein form of the triangle), the test that rules lines out before Newton (never a
// line that crosses, always one that passes well outside), and the crossing Newton finds.
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

// A random curved P2 triangle: the unit triangle's nodes moved by up to `amplitude`.
std::vector<double> random_displacement(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> u(18);
  for (double& v : u) v = amplitude * U(rng);
  return u;
}

// A point of the reference triangle, a sixth of them on an edge or at a vertex.
Param random_parameter(std::mt19937& rng) {
  std::uniform_real_distribution<double> U(0, 1);
  double a = U(rng), b = U(rng);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  switch (rng() % 12) {
    case 0: return Param(a, 0);
    case 1: return Param(0, b);
    case 2: return Param(a, 1 - a);
    case 3: return Param(rng() % 2, 0);
    default: return Param(a, b);
  }
}

// x(eta) = sum_i lambda_i^2 P_i + 2 sum_(i,j) lambda_i lambda_j P_ij over the control net, to
// round-off, for both quadratic bases and for a flat P1 triangle.
TEST(FacetProjection, ControlNetIsTheTrianglesBernsteinForm) {
  std::mt19937 rng(7);
  for (const auto& [kind, n] : {std::pair{fem::BasisKind::P2Nodal, 6}, std::pair{fem::BasisKind::P2Hierarchical, 6},
                                std::pair{fem::BasisKind::P1, 3}}) {
    const facets::FacetEvaluator<3> ev(kind, n);
    SurfaceFacet f = unit_triangle(n);
    if (n == 6) {  // a curved reference facet as well
      f.curved = true;
      f.offset[1][2] = 0.1;
    }
    std::vector<double> u = random_displacement(rng, 0.2);
    u.resize(static_cast<size_t>(3 * n));
    const auto net = ev.control_net(f, u);
    for (int trial = 0; trial < 50; ++trial) {
      const Param eta = random_parameter(rng);
      const double l[3] = {1 - eta.sum(), eta[0], eta[1]};
      Vec bernstein = Vec::Zero();
      for (int i = 0; i < 3; ++i) bernstein += l[i] * l[i] * net[i] + 2 * l[i] * l[(i + 1) % 3] * net[3 + i];
      EXPECT_LT((ev.at(f, eta, u).x - bernstein).norm(), 1e-14) << "basis " << fem::to_string(kind);
    }
  }
}

// Lines through random points of curved P2 triangles (nodes moved by up to 0.15), in random
// directions: the test never rules one out. On gentler triangles (0.05), Newton finds each
// crossing (to 1e-12) of a line within 45 degrees of the normal. Lines through points outside the triangle (a
// parameter 0.3 beyond an edge), within 30 degrees of the normal of a gently curved one: all
// ruled out.
TEST(FacetProjection, LineTestRulesOutOnlyLinesThatMissTheTriangle) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  const facets::FacetEvaluator<3> ev(fem::BasisKind::P2Nodal, 6);
  const SurfaceFacet f = unit_triangle(6);
  auto direction_near = [&](const Vec& normal, double max_angle) {
    for (;;) {
      const Vec v(U(rng), U(rng), U(rng));
      const Vec d = normal.normalized() + std::tan(max_angle) * v;
      if (v.norm() <= 1 && std::acos(d.normalized().dot(normal.normalized())) <= max_angle) return d;
    }
  };
  int newton_checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const bool steep = trial % 2 == 0;
    const std::vector<double> u = random_displacement(rng, steep ? 0.05 : 0.15);
    const Param eta = random_parameter(rng);
    const facets::FacetPoint<3> y = ev.at(f, eta, u);
    const Vec normal = y.dx.col(0).cross(y.dx.col(1));
    const Vec nu = steep ? direction_near(normal, M_PI / 4) : Vec(U(rng), U(rng), U(rng));
    const double t = U(rng);
    const Vec x = y.x - t * nu;
    ASSERT_TRUE(facets::line_may_cross(ev.control_net(f, u), x, nu)) << "trial " << trial;
    const bool inside = eta.minCoeff() > 1e-3 && eta.sum() < 1 - 1e-3;
    if (!steep || !inside) continue;
    const auto p = facets::intersect<3>(ev, f, x, nu, u);
    ASSERT_TRUE(p.found) << "trial " << trial;
    EXPECT_LT((p.eta - eta).norm(), 1e-12) << "trial " << trial;
    EXPECT_NEAR(p.t, t, 1e-12) << "trial " << trial;
    ++newton_checked;
  }
  EXPECT_GT(newton_checked, 400);
  int ruled_out = 0;
  const Param outside[] = {Param(-0.3, 0.4), Param(0.4, -0.3), Param(0.65, 0.65), Param(-0.3, -0.3), Param(1.3, 0.1)};
  for (int trial = 0; trial < 500; ++trial) {
    const std::vector<double> u = random_displacement(rng, 0.01);
    const facets::FacetPoint<3> y = ev.at(f, outside[trial % 5], u);  // the quadratic map extended
    const Vec normal = y.dx.col(0).cross(y.dx.col(1));
    const Vec nu = direction_near(normal, M_PI / 6);
    ruled_out += !facets::line_may_cross(ev.control_net(f, u), y.x - U(rng) * nu, nu);
  }
  EXPECT_EQ(ruled_out, 500);
}

}  // namespace
}  // namespace stiction::contact
