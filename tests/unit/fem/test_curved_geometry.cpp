// Curved (isoparametric P2) geometry: edge midpoints on the true boundary, refinement that
// follows the level-0 arcs, exact-geometry areas, and a thick cylinder under pressure
// against Lame's solution. Every test compares with the same mesh on its chords (the
// midpoints dropped), which is what the code did before cells were curved.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "fem/error_norms.hpp"
#include "materials/material.hpp"
#include "common/error.hpp"
#include "mesh/gmsh_io.hpp"
#include "support/manufactured.hpp"

namespace stiction {
namespace {

using fem::BasisKind;

mesh::Mesh chords_of(mesh::Mesh m) {
  m.edge_midpoints.clear();
  return m;
}

// The quarter disc of radius 1 (sides "x-axis", "arc", "y-axis"), or with inner radius > 0
// the quarter annulus (sides "bottom", "outer", "left", "inner").
mesh::Mesh quarter(double inner, double h) {
  mesh::PolygonSpec spec;
  spec.h = h;
  if (inner > 0) {
    spec.xy = {inner, 0, 2 * inner, 0, 0, 2 * inner, 0, inner};
    spec.names = {"bottom", "outer", "left", "inner"};
    spec.arc_centers = {{1, {0, 0}}, {3, {0, 0}}};
  } else {
    spec.xy = {0, 0, 1, 0, 0, 1};
    spec.names = {"x-axis", "arc", "y-axis"};
    spec.arc_centers = {{1, {0, 0}}};
  }
  return mesh::generate_polygon(spec);
}

// Area of the mesh as the space maps it: ||1||_L2^2 by the error norm of u = 0 against 1.
double mapped_area(const mesh::Mesh& m, BasisKind kind) {
  const fem::FieldSpace space(m, kind);
  const std::vector<double> zero(space.n_dofs(), 0.0);
  const auto e = fem::compute_errors(
      space, zero, [](const double*, double* u) { u[0] = 1, u[1] = 0; },
      [](const double*, double* g) { std::fill(g, g + 4, 0.0); }, 6);
  return e.l2 * e.l2;
}

// Largest distance of the arc's vertices from the unit circle.
double max_radius_error(const mesh::Mesh& m) {
  double worst = 0;
  for (int f = 0; f < m.n_facets(); ++f) {
    if (m.facet_tags[f] != m.facet_tag_names.at("arc")) continue;
    for (int k = 0; k < m.dim; ++k) {
      const double* X = m.vertex(m.facet(f)[k]);
      worst = std::max(worst, std::abs(std::hypot(X[0], X[1]) - 1));
    }
  }
  return worst;
}

TEST(CurvedGeometry, GmshPlacesTheArcsEdgeMidpointsOnTheCircle) {
  const mesh::Mesh m = quarter(0, 0.2);
  int arc_facets = 0;
  for (int tag : m.facet_tags) arc_facets += tag == m.facet_tag_names.at("arc");
  ASSERT_GT(arc_facets, 5);
  EXPECT_EQ(static_cast<int>(m.edge_midpoints.size()), arc_facets);  // the straight sides have none
  for (const auto& [edge, mid] : m.edge_midpoints) EXPECT_NEAR(std::hypot(mid[0], mid[1]), 1.0, 1e-9);
  const fem::FieldSpace p2(m, BasisKind::P2Hierarchical), p1(m, BasisKind::P1);
  EXPECT_TRUE(p2.is_curved());
  EXPECT_FALSE(p1.is_curved());  // P1 keeps the chords
}

// A second-order .msh file: the edge nodes off their chords become curved edges.
TEST(CurvedGeometry, SecondOrderMshFileKeepsItsCurvedEdges) {
  const std::string path = ::testing::TempDir() + "/curved-triangle.msh";
  {
    std::ofstream out(path);
    // One 6-node triangle (Gmsh type 9: corners, then edges 01 12 20): edge 01 bent down by
    // 0.1, edge 12 out by 0.05 along x and y, edge 20 straight.
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 1 0\n1 0 0 0 1 1 0 0 0\n$EndEntities\n"
           "$Nodes\n1 6 1 6\n2 1 0 6\n1\n2\n3\n4\n5\n6\n0 0 0\n1 0 0\n0 1 0\n0.5 -0.1 0\n0.55 0.55 0\n0 0.5 0\n"
           "$EndNodes\n$Elements\n1 1 1 1\n2 1 9 1\n1 1 2 3 4 5 6\n$EndElements\n";
  }
  const mesh::Mesh m = mesh::read_msh(path);
  std::remove(path.c_str());
  ASSERT_EQ(m.n_cells(), 1);
  ASSERT_EQ(m.edge_midpoints.size(), 2u);
  const int* v = m.cell(0);
  const auto bent = m.edge_midpoints.at({std::min(v[0], v[1]), std::max(v[0], v[1])});
  EXPECT_DOUBLE_EQ(bent[0], 0.5);
  EXPECT_DOUBLE_EQ(bent[1], -0.1);
  EXPECT_EQ(m.edge_midpoints.count({std::min(v[0], v[2]), std::max(v[0], v[2])}), 0u);
  // Area of the quadratic triangle: a parabolic bulge of height |offset| over a chord of
  // length L adds (2/3) |offset| L: 0.1 x 1 for edge 01, 0.05 sqrt(2) x sqrt(2) for edge 12.
  EXPECT_NEAR(mapped_area(m, BasisKind::P2Hierarchical), 0.5 + 2.0 / 3 * 0.1 + 2.0 / 3 * 0.1, 1e-12);
}

// The quadratic arcs hold the circle's area to O(h^4) per facet; the chords lose O(h^2).
TEST(CurvedGeometry, TheCurvedCellsCoverTheQuarterDisc) {
  const mesh::Mesh m = quarter(0, 0.2);
  const double exact = M_PI / 4;
  const double curved = std::abs(mapped_area(m, BasisKind::P2Hierarchical) - exact);
  const double nodal = std::abs(mapped_area(m, BasisKind::P2Nodal) - exact);
  const double chord = std::abs(mapped_area(chords_of(m), BasisKind::P2Hierarchical) - exact);
  const double p1 = std::abs(mapped_area(m, BasisKind::P1) - exact);
  std::printf("area error: curved P2 %.3e, nodal %.3e, chords %.3e, P1 %.3e\n", curved, nodal, chord, p1);
  EXPECT_GT(chord, 1e-4);
  EXPECT_NEAR(p1, chord, 1e-14);
  EXPECT_LT(curved, 1e-2 * chord);
  EXPECT_NEAR(nodal, curved, 1e-14);
}

// Red refinement puts the new boundary vertices on the level-0 quadratic arcs, not on the
// chords: the distance to the circle shrinks with the arcs' O(h^3) error, not O(h^2).
TEST(CurvedGeometry, RefinementFollowsTheLevelZeroArcs) {
  const mesh::Mesh m = quarter(0, 0.2);
  const mesh::Mesh curved = mesh::refine(m, 2), chord = mesh::refine(chords_of(m), 2);
  ASSERT_EQ(curved.n_vertices(), chord.n_vertices());
  EXPECT_NO_THROW(mesh::check_validity(curved, "refined quarter disc"));
  EXPECT_FALSE(curved.edge_midpoints.empty());
  EXPECT_TRUE(chord.edge_midpoints.empty());
  std::printf("max |r - 1| after two refinements: curved %.3e, chords %.3e\n", max_radius_error(curved),
              max_radius_error(chord));
  EXPECT_LT(max_radius_error(curved), 0.05 * max_radius_error(chord));
  // The fine mesh's own midpoints stay on the level-0 map: its area is the level-0 area.
  EXPECT_NEAR(mapped_area(curved, BasisKind::P2Hierarchical), mapped_area(m, BasisKind::P2Hierarchical), 1e-12);
}

// A cell whose curved midpoint crosses the opposite side is folded and refused.
TEST(CurvedGeometry, ValidityRefusesAFoldedCurvedCell) {
  mesh::Mesh m = mesh::structured_box(2, {1, 1, 1}, {1, 1, 1});
  const int a = m.cell(0)[0], b = m.cell(0)[1];
  double mid[3];
  for (int k = 0; k < 2; ++k) mid[k] = 0.5 * (m.vertex(a)[k] + m.vertex(b)[k]);
  const double* opposite = m.vertex(m.cell(0)[2]);
  // Push the midpoint of edge (a, b) 1.2 times past the opposite vertex.
  m.edge_midpoints[{std::min(a, b), std::max(a, b)}] = {mid[0] + 1.2 * (opposite[0] - mid[0]),
                                                          mid[1] + 1.2 * (opposite[1] - mid[1]), 0};
  try {
    mesh::check_validity(m, "bent square");
    FAIL() << "a folded curved cell was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is folded"), std::string::npos) << e.what();
  }
}

// Lame's thick cylinder (plane strain, inner radius a = 1, outer b = 2, internal pressure p):
// u_r = (1 + nu) p a^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r). Quarter model, symmetry
// on the straight sides, the pressure as a dead radial traction on the inner arc.
struct Lame {
  double E = 1, nu = 0.3, p = 1e-3, a = 1, b = 2;
  double radial(double r) const { return (1 + nu) * p * a * a / (E * (b * b - a * a)) * ((1 - 2 * nu) * r + b * b / r); }
  double slope(double r) const { return (1 + nu) * p * a * a / (E * (b * b - a * a)) * ((1 - 2 * nu) - b * b / (r * r)); }
};

double cylinder_error(const mesh::Mesh& m) {
  const Lame lame;
  const fem::FieldSpace space(m, BasisKind::P2Hierarchical);
  materials::LinearElastic law(lame.E, lame.nu);
  nonlinear::ElasticityProblem problem;
  problem.space = &space;
  problem.cell_material.assign(m.n_cells(), &law);
  const auto zero = [](const double*, double, double* u) { u[0] = u[1] = 0; };
  problem.dirichlet.push_back({"bottom", m.facet_tag_names.at("bottom"), {1}, zero});
  problem.dirichlet.push_back({"left", m.facet_tag_names.at("left"), {0}, zero});
  problem.tractions.push_back({"inner", m.facet_tag_names.at("inner"), [&lame](const double* X, double, double* t) {
                                 const double r = std::hypot(X[0], X[1]);
                                 t[0] = lame.p * X[0] / r, t[1] = lame.p * X[1] / r;
                               }});
  const std::vector<double> u = test::solve_in_one_step(problem);
  const auto exact = [&lame](const double* X, double* u) {
    const double r = std::hypot(X[0], X[1]);
    u[0] = lame.radial(r) * X[0] / r, u[1] = lame.radial(r) * X[1] / r;
  };
  // grad(u_r(r) e_r) = u_r' e_r e_r + (u_r / r) (I - e_r e_r).
  const auto gradient = [&lame](const double* X, double* g) {
    const double r = std::hypot(X[0], X[1]), n[2] = {X[0] / r, X[1] / r};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        g[i * 2 + j] = lame.slope(r) * n[i] * n[j] + lame.radial(r) / r * ((i == j ? 1.0 : 0.0) - n[i] * n[j]);
  };
  return fem::compute_errors(space, u, exact, gradient, 6).l2;
}

TEST(CurvedGeometry, ThickCylinderConvergesAtTheP2RateOnlyWithCurvedCells) {
  const mesh::Mesh coarse = quarter(1, 0.25), fine = quarter(1, 0.125);
  const double curved_coarse = cylinder_error(coarse), curved_fine = cylinder_error(fine);
  const double chord_coarse = cylinder_error(chords_of(coarse)), chord_fine = cylinder_error(chords_of(fine));
  const double curved_rate = std::log2(curved_coarse / curved_fine), chord_rate = std::log2(chord_coarse / chord_fine);
  std::printf("L2 error h = 0.25 -> 0.125: curved %.3e -> %.3e (rate %.2f), chords %.3e -> %.3e (rate %.2f)\n",
              curved_coarse, curved_fine, curved_rate, chord_coarse, chord_fine, chord_rate);
  EXPECT_GT(curved_rate, 2.6);
  EXPECT_LT(chord_rate, 2.4);
  EXPECT_LT(curved_fine, 0.2 * chord_fine);
}

}  // namespace
}  // namespace stiction
