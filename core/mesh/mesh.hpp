#pragma once
// Simplicial meshes (triangles in 2D, tetrahedra in 3D) with integer tags on cells (bodies,
// regions) and on boundary facets (Dirichlet, traction and, later, contact surfaces).
//
// Vertex numbering convention used throughout stiction: refine() numbers the new vertices
// after the old ones in edge order, so the vertices of level k+1 are exactly the P2 nodes
// (vertices then edges) of level k, as in the paper's Table 1.
#include <array>
#include <map>
#include <string>
#include <vector>

namespace stiction::mesh {

struct Mesh {
  int dim = 0;
  std::vector<double> coords;  // n_vertices x dim
  std::vector<int> cells;      // n_cells x (dim + 1)
  std::vector<int> cell_tags;  // one per cell
  std::vector<int> facets;     // n_facets x dim: tagged boundary facets only
  std::vector<int> facet_tags; // one per facet
  std::map<std::string, int> cell_tag_names;   // name -> tag
  std::map<std::string, int> facet_tag_names;  // name -> tag
  // Curved edges only: the true midpoint of edge {lo, hi} (vertex indices, lo < hi) where
  // the geometry (Gmsh's CAD model, a generator's exact surface) bends away from the chord.
  // P2 spaces map such cells isoparametrically, X(l) = sum_v X_v l_v + sum_e d_e 4 l_a l_b
  // with d_e = midpoint - chord midpoint (fem/cell_geometry.hpp); P1 spaces keep the chords.
  std::map<std::array<int, 2>, std::array<double, 3>> edge_midpoints;

  int vertices_per_cell() const { return dim + 1; }
  int n_vertices() const { return dim ? static_cast<int>(coords.size()) / dim : 0; }
  int n_cells() const { return dim ? static_cast<int>(cells.size()) / (dim + 1) : 0; }
  int n_facets() const { return dim ? static_cast<int>(facets.size()) / dim : 0; }
  const double* vertex(int v) const { return coords.data() + static_cast<size_t>(v) * dim; }
  const int* cell(int c) const { return cells.data() + static_cast<size_t>(c) * (dim + 1); }
  const int* facet(int f) const { return facets.data() + static_cast<size_t>(f) * dim; }
  bool is_curved() const { return !edge_midpoints.empty(); }
  // d_e of edge (a, b) into out (dim entries): zero on a straight edge.
  void edge_offset(int a, int b, double* out) const;
  // Records mid (dim entries) as the midpoint of edge (a, b) where it leaves the chord by
  // more than round-off (1e-12 of the edge's length); a straight edge records nothing.
  void set_edge_midpoint(int a, int b, const double* mid);
};

// "cell 14090 (vertex centroid (2.862, 3.993))": a cell named so that a user can find it in
// the reference configuration of the mesh (messages about inverted or folded cells).
std::string describe_cell(const Mesh& mesh, int c);

// Local edges of the reference simplex, in VTK's order for quadratic cells
// (tetra: 01 12 20 03 13 23; triangle: 01 12 20) so output needs no permutation.
template <int D>
struct SimplexEdges;
template <>
struct SimplexEdges<1> {
  static constexpr std::array<std::array<int, 2>, 1> list{{{0, 1}}};
};
template <>
struct SimplexEdges<2> {
  static constexpr std::array<std::array<int, 2>, 3> list{{{0, 1}, {1, 2}, {2, 0}}};
};
template <>
struct SimplexEdges<3> {
  static constexpr std::array<std::array<int, 2>, 6> list{
      {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}};
};
constexpr int n_simplex_edges(int d) { return d * (d + 1) / 2; }
// Local edge e of a d-simplex as a vertex pair.
std::array<int, 2> simplex_edge(int d, int e);

// Unique edges of a mesh with the cell -> edge and facet -> edge incidences.
struct EdgeTopology {
  std::vector<std::array<int, 2>> edges;  // sorted lexicographically, (lo, hi)
  std::vector<int> cell_edges;            // n_cells x n_simplex_edges(dim), local order above
  std::vector<int> facet_edges;           // n_facets x n_simplex_edges(dim - 1)
  int n_edges() const { return static_cast<int>(edges.size()); }
  int find(int a, int b) const;           // edge id of (a, b), -1 if absent
};
EdgeTopology build_edges(const Mesh& mesh);

// The n <= 3 vertex ids sorted, padded in front with -1: the same key for a facet and for
// the face of a cell it lies on.
std::array<int, 3> facet_key(const int* v, int n);
// The facets of a cell with vertices v (dim + 1 of them) as keys, the one opposite vertex
// k at k.
std::vector<std::array<int, 3>> cell_facet_keys(const int* v, int dim);

// Uniform refinement: triangle -> 4, tetrahedron -> 8 (red refinement, the interior
// octahedron split along its shortest diagonal); cell and facet tags are kept. On a curved
// mesh the new vertices are the curved edges' midpoints and the children's edges follow the
// parent's quadratic map, so refinement stays on the level-0 geometry to second order.
Mesh refine(const Mesh& mesh);
Mesh refine(const Mesh& mesh, int levels);

// Signed measure (area/volume) of a cell's chords; positive for the reference orientation.
double signed_measure(const Mesh& mesh, int cell);
// A curved cell's quadratic map at barycentric coordinates l (dim + 1 entries): the position
// X and the Jacobian's determinant det(dX/dxi) (the chord cell's at every point when
// straight).
void curved_cell_map(const Mesh& mesh, int cell, const double* l, double* X, double* det);

// Throws stiction::Error naming the first inverted or degenerate cell with its index and
// vertex coordinates; a curved cell must also keep det(dX/dxi) > 0 at its vertices and edge
// midpoints (a midpoint pushed across the opposite side folds the cell). `what` names the
// mesh in the message.
void check_validity(const Mesh& mesh, const std::string& what);

// Appends `part` to `into`: vertex and cell indices are shifted, tags are shifted so they
// stay distinct, and tag names get `prefix` ("block/top"). Returns the tag offsets.
struct TagOffsets {
  int cell = 0;
  int facet = 0;
};
TagOffsets append(Mesh& into, const Mesh& part, const std::string& prefix);

// Axis-aligned bounding-box diagonal (a length scale for tolerances).
double bounding_diagonal(const Mesh& mesh);

// Structured simplicial mesh of a box [0,lx]x[0,ly](x[0,lz]) with n cells per direction
// (2 triangles or 6 tetrahedra per square/cube). Facet tags: xmin=1 xmax=2 ymin=3 ymax=4
// zmin=5 zmax=6, cell tag 1 ("body"). Used by tests and as a Gmsh-free fallback.
Mesh structured_box(int dim, const std::array<double, 3>& lengths, const std::array<int, 3>& n);

}  // namespace stiction::mesh
