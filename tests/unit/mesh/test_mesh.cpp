// Refinement counts and invariants, the validity check, and Gmsh .msh round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "common/error.hpp"
#include "fem/field_space.hpp"
#include "mesh/gmsh_io.hpp"
#include "mesh/grooved_block.hpp"
#include "mesh/local_mesh.hpp"
#include "mesh/mesh.hpp"
#include "mesh/structured_tube.hpp"
#include "support/mesh_checks.hpp"

namespace stiction::mesh {
namespace {

double total_measure(const Mesh& m) {
  double s = 0;
  for (int c = 0; c < m.n_cells(); ++c) s += signed_measure(m, c);
  return s;
}

std::map<int, int> facets_per_tag(const Mesh& m) {
  std::map<int, int> n;
  for (int t : m.facet_tags) ++n[t];
  return n;
}

class Refinement : public ::testing::TestWithParam<int> {};

TEST_P(Refinement, CountsTagsMeasureAndOrientation) {
  const int dim = GetParam();
  const Mesh coarse = structured_box(dim, {2.0, 1.0, 0.5}, {3, 2, 2});
  const Mesh fine = refine(coarse);
  const int children = dim == 2 ? 4 : 8, facet_children = dim == 2 ? 2 : 4;
  EXPECT_EQ(fine.n_cells(), children * coarse.n_cells());
  EXPECT_EQ(fine.n_facets(), facet_children * coarse.n_facets());
  // Vertices of level k+1 are the P2 nodes of level k.
  EXPECT_EQ(fine.n_vertices(), coarse.n_vertices() + build_edges(coarse).n_edges());
  const fem::FieldSpace p2(coarse, fem::BasisKind::P2Hierarchical);
  ASSERT_EQ(p2.n_nodes(), fine.n_vertices());
  for (int n = 0; n < p2.n_nodes(); ++n) {
    double X[3];
    p2.node_position(n, X);
    for (int k = 0; k < dim; ++k) EXPECT_EQ(X[k], fine.vertex(n)[k]);
  }
  EXPECT_NEAR(total_measure(fine), total_measure(coarse), 1e-12);
  for (int c = 0; c < fine.n_cells(); ++c) ASSERT_GT(signed_measure(fine, c), 0) << "cell " << c;
  for (auto [tag, count] : facets_per_tag(coarse)) EXPECT_EQ(facets_per_tag(fine)[tag], facet_children * count);
  for (int c = 0; c < fine.n_cells(); ++c) EXPECT_EQ(fine.cell_tags[c], coarse.cell_tags[c / children]);
  EXPECT_NO_THROW(check_validity(refine(fine), "level 2"));
}

INSTANTIATE_TEST_SUITE_P(Dimensions, Refinement, ::testing::Values(2, 3));

TEST(Refinement, StructuredCubeCounts) {
  // Unit cube in 6 tetrahedra: 8 vertices, 19 edges. Level 1: 48 cells, 27 vertices.
  const Mesh m0 = structured_box(3, {1, 1, 1}, {1, 1, 1});
  EXPECT_EQ(m0.n_cells(), 6);
  EXPECT_EQ(build_edges(m0).n_edges(), 19);
  const Mesh m1 = refine(m0);
  EXPECT_EQ(m1.n_cells(), 48);
  EXPECT_EQ(m1.n_vertices(), 27);
  const Mesh m2 = refine(m0, 2);
  EXPECT_EQ(m2.n_cells(), 384);
  EXPECT_EQ(m2.n_vertices(), 125);
}

TEST(Validity, InvertedElementNamesIndexAndCoordinates) {
  Mesh m = structured_box(3, {1, 1, 1}, {1, 1, 1});
  std::swap(m.cells[3 * 4 + 0], m.cells[3 * 4 + 1]);
  try {
    check_validity(m, "test mesh");
    FAIL() << "no error for an inverted element";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("inverted element 3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("(0, 0, 0)"), std::string::npos) << msg;
  }
}

TEST(Validity, DegenerateElement) {
  Mesh m = structured_box(2, {1, 1, 1}, {2, 2, 1});
  const int v = m.cells[1];
  for (int k = 0; k < 2; ++k) m.coords[v * 2 + k] = m.coords[m.cells[0] * 2 + k];  // collapse an edge
  EXPECT_THROW(
      {
        try {
          check_validity(m, "test mesh");
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("degenerate element"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
}

class GmshRoundTrip : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(GmshRoundTrip, ReadsWhatGmshWrote) {
  const auto [dim, binary] = GetParam();
  const std::array<double, 3> L{2.0, 1.0, 0.5};
  const std::string path = ::testing::TempDir() + "/box-" + std::to_string(dim) + (binary ? "b" : "a") + ".msh";
  write_box_msh(dim, L, 0.25, path, binary);
  const Mesh generated = generate_box(dim, L, 0.25);
  const Mesh read = read_msh(path);
  std::remove(path.c_str());
  EXPECT_EQ(read.dim, dim);
  EXPECT_EQ(read.n_cells(), generated.n_cells());
  EXPECT_EQ(read.n_vertices(), generated.n_vertices());
  EXPECT_GT(read.n_cells(), 50);
  EXPECT_NEAR(total_measure(read), dim == 3 ? 1.0 : 2.0, 1e-10);
  EXPECT_NO_THROW(check_validity(read, path));
  EXPECT_EQ(read.cell_tag_names.at("body"), 1);
  // Each named side carries facets covering exactly its area (length in 2D).
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int t = 0; t < 2 * dim; ++t) {
    ASSERT_EQ(read.facet_tag_names.at(names[t]), t + 1);
    double area = 0;
    for (int f = 0; f < read.n_facets(); ++f) {
      if (read.facet_tags[f] != t + 1) continue;
      const double* a = read.vertex(read.facet(f)[0]);
      const double* b = read.vertex(read.facet(f)[1]);
      if (dim == 2) {
        area += std::hypot(b[0] - a[0], b[1] - a[1]);
      } else {
        const double* c = read.vertex(read.facet(f)[2]);
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        area += 0.5 * std::sqrt(std::pow(u[1] * v[2] - u[2] * v[1], 2) + std::pow(u[2] * v[0] - u[0] * v[2], 2) +
                                std::pow(u[0] * v[1] - u[1] * v[0], 2));
      }
    }
    const int axis = t / 2;
    double expected = 1;
    for (int k = 0; k < dim; ++k)
      if (k != axis) expected *= L[k];
    EXPECT_NEAR(area, expected, 1e-10) << names[t];
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, GmshRoundTrip,
                         ::testing::Combine(::testing::Values(2, 3), ::testing::Values(false, true)),
                         [](const auto& info) {
                           return std::to_string(std::get<0>(info.param)) + "D_" +
                                  (std::get<1>(info.param) ? "binary" : "ascii");
                         });

// The sphere-octant generator: an eighth of the unit ball (volume pi/6, approached from
// below by the flat facets, closer at the finer scale), its four named faces, positive
// cells, and a finer mesh near the pole than far from it.
TEST(SphereOctant, VolumeFacesAndGrading) {
  SphereOctantSpec spec;
  spec.radius = 1.0, spec.h = 0.3, spec.contact_size = 0.05, spec.contact_zone = 0.1;
  const Mesh m = generate_sphere_octant(spec);
  EXPECT_NO_THROW(check_validity(m, "sphere octant"));
  const double volume = total_measure(m) / (M_PI / 6);
  EXPECT_GT(volume, 0.95);
  EXPECT_LT(volume, 1.0);
  SphereOctantSpec finer = spec;
  finer.scale = 0.5;
  const double finer_volume = total_measure(generate_sphere_octant(finer)) / (M_PI / 6);
  EXPECT_GT(finer_volume, volume);
  EXPECT_LT(finer_volume, 1.0);
  for (const char* name : {"surface", "top", "symmetry-x", "symmetry-z"}) EXPECT_TRUE(m.facet_tag_names.count(name)) << name;
  double near_edge = 1e9, far_edge = 0;  // shortest cell edge near the pole, longest far away
  for (int c = 0; c < m.n_cells(); ++c) {
    const double* a = m.vertex(m.cell(c)[0]);
    const double* b = m.vertex(m.cell(c)[1]);
    const double edge = std::sqrt(std::pow(a[0] - b[0], 2) + std::pow(a[1] - b[1], 2) + std::pow(a[2] - b[2], 2));
    const double from_pole = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (from_pole < 0.05) near_edge = std::min(near_edge, edge);
    if (from_pole > 0.8) far_edge = std::max(far_edge, edge);
  }
  EXPECT_LT(near_edge, 0.1);
  EXPECT_GT(far_edge, 0.15);
  spec.contact_size = 0.5;  // above h
  EXPECT_THROW(generate_sphere_octant(spec), Error);
}

// Gmsh's options outlive its model: a graded polygon meshes alike before and after a sphere
// octant (whose generator turns sizing from points off) in the same process.
TEST(Generators, PolygonGradingSurvivesASphereOctant) {
  PolygonSpec polygon;
  polygon.xy = {0.0, 0.0, 4.0, 0.0, 4.0, 1.0, 0.0, 1.0};
  polygon.names = {"base", "right", "top", "left"};
  polygon.h = 0.5;
  polygon.point_sizes = {0.5, 0.5, 0.05, 0.05};
  const int before = generate_polygon(polygon).n_cells();
  SphereOctantSpec octant;
  octant.radius = 1.0, octant.h = 0.5, octant.contact_size = 0.2;
  generate_sphere_octant(octant);
  EXPECT_EQ(generate_polygon(polygon).n_cells(), before);
  EXPECT_GT(before, 2 * 4 * 2 * 2) << "the point sizes grade the mesh well below h";
}

// Mean length of the edges of the facets named `name`.
double mean_facet_edge(const Mesh& m, const std::string& name) {
  const int tag = m.facet_tag_names.at(name), d = m.dim;
  double sum = 0;
  int n = 0;
  for (int f = 0; f < m.n_facets(); ++f) {
    if (m.facet_tags[f] != tag) continue;
    for (int k = 0; k < d; ++k) {
      const double* a = m.vertex(m.facet(f)[k]);
      const double* b = m.vertex(m.facet(f)[(k + 1) % d]);
      double e = 0;
      for (int c = 0; c < d; ++c) e += (a[c] - b[c]) * (a[c] - b[c]);
      sum += std::sqrt(e), ++n;
      if (d == 2) break;  // a segment has one edge
    }
  }
  return sum / n;
}

// A size field on one side of a 4 x 3 rectangle (h = 0.5): edges of about 0.05 there, of h
// on the opposite side (3 away, beyond the field's distance 2), in 2D and extruded to 3D.
// Without the field every side is meshed at h.
TEST(Generators, PolygonSizeFieldGradesFromANamedSide) {
  for (double thickness : {0.0, 0.5}) {
    SCOPED_TRACE(thickness);
    PolygonSpec spec;
    spec.xy = {0.0, 0.0, 4.0, 0.0, 4.0, 3.0, 0.0, 3.0};
    spec.names = {"base", "right", "top", "left"};
    spec.h = 0.5;
    spec.thickness = thickness;
    const double uniform_top = mean_facet_edge(generate_polygon(spec), "top");
    spec.size_fields = {{"top", thickness > 0 ? 0.1 : 0.05, 2.0}};
    const Mesh m = generate_polygon(spec);
    EXPECT_NO_THROW(check_validity(m, "graded polygon"));
    const double top = mean_facet_edge(m, "top"), base = mean_facet_edge(m, "base");
    EXPECT_GT(uniform_top, 0.35);
    EXPECT_LT(top, 1.5 * spec.size_fields[0].size);
    EXPECT_GT(top, 0.6 * spec.size_fields[0].size);
    EXPECT_GT(base, 0.35);
  }
}

TEST(Generators, SizeFieldOnAnUnknownSideNamesTheSides) {
  PolygonSpec spec;
  spec.xy = {0.0, 0.0, 1.0, 0.0, 1.0, 1.0};
  spec.names = {"a", "b", "c"};
  spec.h = 0.5;
  spec.size_fields = {{"d", 0.1, 0.5}};
  try {
    generate_polygon(spec);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no boundary named 'd'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a, b, c"), std::string::npos) << e.what();
  }
  spec.size_fields = {{"a", 0.6, 0.5}};  // above h
  EXPECT_THROW(generate_polygon(spec), Error);
}

// A .geo script (OpenCASCADE disk of radius 1, its rim a named curve) meshed through the
// Gmsh library: the rim's vertices lie on the circle at every size factor, the area
// approaches pi from below as the mesh is refined, and halving the sizes gives about four
// times the cells.
TEST(GeoScript, MeshedAtEachLevelWithVerticesOnTheCurvedBoundary) {
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "disk.geo";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("SetFactory(\"OpenCASCADE\");\nDisk(1) = {0, 0, 0, 1};\nPhysical Surface(\"body\") = {1};\n"
               "Physical Curve(\"rim\") = {1};\nMesh.MeshSizeMax = 0.2;\n", f);
    std::fclose(f);
  }
  const Mesh coarse = mesh_geo(path.string(), 1.0), fine = mesh_geo(path.string(), 0.5);
  for (const Mesh* m : {&coarse, &fine}) {
    EXPECT_NO_THROW(check_validity(*m, "disk"));
    ASSERT_TRUE(m->facet_tag_names.count("rim"));
    for (int f = 0; f < m->n_facets(); ++f)
      for (int k = 0; k < 2; ++k) EXPECT_NEAR(std::hypot(m->vertex(m->facet(f)[k])[0], m->vertex(m->facet(f)[k])[1]), 1.0, 1e-9);
  }
  const double a0 = total_measure(coarse), a1 = total_measure(fine);
  EXPECT_LT(a0, a1);
  EXPECT_LT(a1, M_PI);
  EXPECT_GT(a0, 0.98 * M_PI);
  EXPECT_GT(fine.n_cells(), 3 * coarse.n_cells());
  EXPECT_LT(fine.n_cells(), 5 * coarse.n_cells());
  EXPECT_THROW(mesh_geo("/nonexistent/shape.geo", 1.0), Error);
}

// A half tube along x (the crossed tubes' upper one): every cell positive, the volume that
// of the polygonal ring whose vertices lie on both cylinders (n cells of angle d: n (Ro^2 -
// Ri^2) sin(d) / 2 times the length, exact), every "inner" / "outer" vertex on its cylinder,
// "start" and "end" at the axial ends, "side0" / "side1" in the plane z = 0.
TEST(Generators, TubeVerticesLieOnTheCylinders) {
  TubeSpec spec;
  spec.inner_radius = 11.2, spec.thickness = 0.8, spec.length = 50;
  spec.axis = 0, spec.center = {0, 24, 0}, spec.angles_degrees = {0, 180}, spec.cells = {2, 12, 4};
  const Mesh m = structured_tube(spec);
  for (int c = 0; c < m.n_cells(); ++c) ASSERT_GT(signed_measure(m, c), 0) << c;
  const double d = M_PI / 12, Ro = 12.0, Ri = 11.2;
  EXPECT_NEAR(total_measure(m), 12 * (Ro * Ro - Ri * Ri) * std::sin(d) / 2 * 50, 1e-10 * 50 * Ro * Ro);
  std::map<std::string, int> checked;
  for (int f = 0; f < m.n_facets(); ++f) {
    std::string name;
    for (const auto& [n, tag] : m.facet_tag_names)
      if (tag == m.facet_tags[f]) name = n;
    for (int k = 0; k < 3; ++k) {
      const double* x = m.vertex(m.facet(f)[k]);
      const double r = std::hypot(x[1] - 24, x[2]);
      if (name == "inner") { EXPECT_NEAR(r, Ri, 1e-12); }
      if (name == "outer") { EXPECT_NEAR(r, Ro, 1e-12); }
      if (name == "start") { EXPECT_NEAR(x[0], 0, 1e-12); }
      if (name == "end") { EXPECT_NEAR(x[0], 50, 1e-12); }
      if (name == "side0" || name == "side1") { EXPECT_NEAR(x[2], 0, 1e-12); }
    }
    ++checked[name];
  }
  // Two triangles per boundary quadrilateral.
  EXPECT_EQ(checked["inner"], 2 * 12 * 4);
  EXPECT_EQ(checked["outer"], 2 * 12 * 4);
  EXPECT_EQ(checked["start"], 2 * 2 * 12);
  EXPECT_EQ(checked["side0"], 2 * 2 * 4);
  EXPECT_EQ(checked["side1"], 2 * 2 * 4);
  EXPECT_EQ(checked.size(), 6u);
}

// On one process the part is the whole mesh, and refining it in parts is mesh::refine, ids,
// coordinates and curved edges alike (the tube's cylinders are curved). The np = 2 version:
// tests/mpi/test_local_mesh.cpp.
TEST(LocalMesh, OneProcessPartIsTheWholeMeshAndRefinesAsIt) {
  TubeSpec spec;
  spec.inner_radius = 11.2, spec.thickness = 0.8, spec.length = 50;
  spec.axis = 0, spec.center = {0, 24, 0}, spec.angles_degrees = {0, 180}, spec.cells = {2, 6, 3};
  const Mesh whole = structured_tube(spec);
  ASSERT_TRUE(whole.is_curved());
  LocalMesh part = local_part(whole, std::vector<int>(whole.n_cells(), 0), 0);
  test::expect_same_mesh(part.mesh, whole);
  EXPECT_EQ(part.n_own_cells, whole.n_cells());
  for (int level = 1; level <= 2; ++level) {
    part = refine_parts(MPI_COMM_SELF, part);
    const Mesh fine = refine(whole, level);
    test::expect_same_mesh(part.mesh, fine);
    EXPECT_EQ(part.n_global_vertices, fine.n_vertices());
    EXPECT_EQ(part.n_own_cells, fine.n_cells());
  }
}

// inner_split names the inner cylinder in two halves at the angle given: every "inner0"
// vertex at an angle up to it, every "inner1" vertex from it on (angle from +y towards +z
// for a tube along x), as many facets in each as cells on each side, and no "inner" left.
TEST(Generators, TubeInnerSplitNamesTwoHalvesAtTheAngle) {
  TubeSpec spec;
  spec.inner_radius = 11.2, spec.thickness = 0.8, spec.length = 50;
  spec.axis = 0, spec.center = {0, 24, 0}, spec.angles_degrees = {0, 180}, spec.cells = {2, 12, 4};
  spec.inner_split_degrees = 60;
  const Mesh m = structured_tube(spec);
  ASSERT_EQ(m.facet_tag_names.count("inner"), 0u);
  const int tag0 = m.facet_tag_names.at("inner0"), tag1 = m.facet_tag_names.at("inner1");
  int n0 = 0, n1 = 0;
  for (int f = 0; f < m.n_facets(); ++f) {
    if (m.facet_tags[f] != tag0 && m.facet_tags[f] != tag1) continue;
    (m.facet_tags[f] == tag0 ? n0 : n1)++;
    for (int k = 0; k < 3; ++k) {
      const double* x = m.vertex(m.facet(f)[k]);
      const double angle = std::atan2(x[2], x[1] - 24) * 180 / M_PI;
      EXPECT_NEAR(std::hypot(x[1] - 24, x[2]), 11.2, 1e-12);
      if (m.facet_tags[f] == tag0) EXPECT_LE(angle, 60 + 1e-9);
      else EXPECT_GE(angle, 60 - 1e-9);
    }
  }
  EXPECT_EQ(n0, 2 * 4 * 4);
  EXPECT_EQ(n1, 2 * 8 * 4);
  spec.inner_split_degrees = 180;
  EXPECT_THROW(structured_tube(spec), Error);
}

TEST(Generators, TubeRejectsBadDimensions) {
  TubeSpec spec;
  spec.inner_radius = 1, spec.thickness = 0.1, spec.length = 2;
  spec.angles_degrees = {0, 360};
  EXPECT_THROW(structured_tube(spec), Error);
  spec.angles_degrees = {0, 90}, spec.thickness = 0;
  EXPECT_THROW(structured_tube(spec), Error);
}

// Where each named face of a grooved block lies: every facet's vertices on its plane, the
// strip bottoms outside the grooves and the floors inside them, each wall at one groove's
// x0 ("left", the cell behind it on the -x side: outward normal +x) or x1 ("right", cell on
// the +x side: normal -x) and below the groove depth. Returns facets per name.
std::map<std::string, int> check_grooved_faces(const Mesh& m, const GroovedBlockSpec& spec) {
  const auto& L = spec.size;
  const double d = spec.groove_depth;
  std::map<std::set<int>, int> opposite;  // facet's vertex set -> the cell's fourth vertex
  for (int c = 0; c < m.n_cells(); ++c)
    for (int k = 0; k < 4; ++k) {
      std::set<int> face;
      for (int j = 0; j < 4; ++j)
        if (j != k) face.insert(m.cell(c)[j]);
      opposite[face] = m.cell(c)[k];
    }
  // The plane each face lies in: axis and coordinate (walls: checked below).
  const std::map<std::string, std::pair<int, double>> plane{{"top", {2, L[2]}},       {"strip-bottom", {2, 0.0}},
                                                            {"groove-floor", {2, d}}, {"xmin", {0, 0.0}},
                                                            {"xmax", {0, L[0]}},      {"ymin", {1, 0.0}},
                                                            {"ymax", {1, L[1]}}};
  std::map<std::string, int> count;
  std::map<std::string, std::set<int>> grooves_reached;
  for (int f = 0; f < m.n_facets(); ++f) {
    std::string name;
    for (const auto& [n, tag] : m.facet_tag_names)
      if (tag == m.facet_tags[f]) name = n;
    ++count[name];
    const int* v = m.facet(f);
    double centre[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) centre[c] += m.vertex(v[k])[c] / 3;
    const bool wall = name == "groove-wall-left" || name == "groove-wall-right";
    const auto on = plane.find(name);
    EXPECT_TRUE(wall || on != plane.end()) << "unexpected facet group '" << name << "'";
    for (int k = 0; k < 3; ++k) {
      const double* x = m.vertex(v[k]);
      if (on != plane.end()) {
        EXPECT_NEAR(x[on->second.first], on->second.second, 1e-12) << name;
      }
      if (wall) {
        EXPECT_NEAR(x[0], centre[0], 1e-12) << name;
        EXPECT_LE(x[2], d + 1e-12) << name;
      }
    }
    int inside = -1;  // the groove the facet's centre lies over, if any
    for (int i = 0; i < spec.grooves; ++i)
      if (centre[0] > groove_span(spec, i)[0] && centre[0] < groove_span(spec, i)[1]) inside = i;
    if (name == "strip-bottom") {
      EXPECT_EQ(inside, -1) << "strip bottom under groove " << inside;
    }
    if (name == "groove-floor") {
      EXPECT_GE(inside, 0) << "groove floor at x = " << centre[0];
      grooves_reached[name].insert(inside);
    }
    if (name != "groove-wall-left" && name != "groove-wall-right") continue;
    const bool left = name == "groove-wall-left";
    int groove = -1;
    for (int i = 0; i < spec.grooves; ++i)
      if (std::abs(centre[0] - groove_span(spec, i)[left ? 0 : 1]) < 1e-12) groove = i;
    EXPECT_GE(groove, 0) << name << " facet at x = " << centre[0];
    grooves_reached[name].insert(groove);
    const auto cell = opposite.find(std::set<int>(v, v + 3));
    if (cell == opposite.end()) {
      ADD_FAILURE() << name << " facet bounds no cell";
      continue;
    }
    const double behind = m.vertex(cell->second)[0] - centre[0];  // material side
    EXPECT_LT(left ? behind : -behind, 0) << name << " at x = " << centre[0] << " faces the wrong way";
  }
  for (const char* n : {"groove-wall-left", "groove-wall-right", "groove-floor"})
    EXPECT_EQ(grooves_reached[n].size(), static_cast<size_t>(spec.grooves)) << n;
  return count;
}

// A small grooved block (3 grooves) and its uniform refinement: every named face present
// and where it belongs, positive cells, the volume lx ly lz - n w d ly to round-off (the
// faces are flat, so the mesh fills the geometry exactly), refinement keeping all of it.
TEST(GroovedBlock, FacesWhereTheyBelongAndExactVolume) {
  GroovedBlockSpec spec;
  spec.size = {20, 10, 6}, spec.grooves = 3, spec.groove_width = 1, spec.groove_depth = 2.5;
  spec.h = 2.5, spec.contact_size = 1.2;
  const Mesh coarse = generate_grooved_block(spec);
  const auto& L = spec.size;
  const double volume = L[0] * L[1] * L[2] - spec.grooves * spec.groove_width * spec.groove_depth * L[1];
  for (const Mesh& m : {coarse, refine(coarse)}) {
    SCOPED_TRACE(m.n_cells());
    EXPECT_NO_THROW(check_validity(m, "grooved block"));
    EXPECT_NEAR(total_measure(m), volume, 1e-9 * volume);
    EXPECT_EQ(m.cell_tag_names.at("body"), 1);
    const std::map<std::string, int> count = check_grooved_faces(m, spec);
    EXPECT_EQ(m.facet_tag_names.size(), 9u);
    for (const char* n : {"top", "strip-bottom", "groove-wall-left", "groove-wall-right", "groove-floor", "xmin", "xmax",
                          "ymin", "ymax"}) {
      EXPECT_TRUE(m.facet_tag_names.count(n)) << n;
      EXPECT_GT(count.count(n) ? count.at(n) : 0, 0) << n;
    }
  }
}

// Grooves that do not fit, a depth through the block, sizes out of range: clear errors.
TEST(GroovedBlock, BadSpecsAreRejected) {
  auto message = [](const GroovedBlockSpec& s) -> std::string {
    try {
      generate_grooved_block(s);
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  GroovedBlockSpec s;
  s.grooves = 50, s.groove_width = 1;  // 50 grooves 1 wide fill lx = 50
  EXPECT_NE(message(s).find("do not fit in lx = 50"), std::string::npos) << message(s);
  s = {}, s.groove_depth = 16;
  EXPECT_NE(message(s).find("groove_depth = 16 must lie in (0, lz = 16)"), std::string::npos) << message(s);
  s = {}, s.grooves = 0;
  EXPECT_NE(message(s).find("at least one groove"), std::string::npos) << message(s);
  s = {}, s.contact_size = 2 * s.h;
  EXPECT_NE(message(s).find("at most h"), std::string::npos) << message(s);
  s = {}, s.groove_width = 0;
  EXPECT_NE(message(s).find("groove_width must be positive"), std::string::npos) << message(s);
  s = {}, s.size[1] = -1;
  EXPECT_NE(message(s).find("side length"), std::string::npos) << message(s);
}

// The paper's block with strips at the defaults. Level 0 against Table 1 (2 654 vertices,
// 9 714 tetrahedra, within 10%); the multiplier nodes (strip bottoms and left walls, each
// pair with its own nodes, so the walls' bottom edges twice) near 3 771 multipliers / 3 =
// 1 257. Measured (Gmsh 4.8.4): 2 675 vertices, 8 900 tetrahedra, 818 on the strip
// bottoms, 525 on the left walls.
TEST(GroovedBlock, CountsNearThePapersLevel0) {
  const Mesh m = generate_grooved_block(GroovedBlockSpec{});
  EXPECT_NO_THROW(check_validity(m, "grooved block"));
  check_grooved_faces(m, GroovedBlockSpec{});
  EXPECT_NEAR(m.n_vertices(), 2654, 0.1 * 2654);
  EXPECT_NEAR(m.n_cells(), 9714, 0.1 * 9714);
  std::map<std::string, std::set<int>> on;  // vertices of each facet group
  for (int f = 0; f < m.n_facets(); ++f)
    for (const auto& [name, tag] : m.facet_tag_names)
      if (tag == m.facet_tags[f]) on[name].insert(m.facet(f), m.facet(f) + 3);
  EXPECT_NEAR(static_cast<double>(on["strip-bottom"].size() + on["groove-wall-left"].size()), 1257, 0.1 * 1257);
  // Walls mirror each other: about as many vertices on each side.
  EXPECT_NEAR(static_cast<double>(on["groove-wall-left"].size()), static_cast<double>(on["groove-wall-right"].size()),
              0.1 * on["groove-wall-right"].size());
  // Deterministic: the same spec gives the same mesh.
  const Mesh again = generate_grooved_block(GroovedBlockSpec{});
  EXPECT_EQ(again.coords, m.coords);
  EXPECT_EQ(again.cells, m.cells);
}

TEST(GmshRead, MissingFileIsAnError) {
  EXPECT_THROW(read_msh("/nonexistent/mesh.msh"), Error);
}

}  // namespace
}  // namespace stiction::mesh
