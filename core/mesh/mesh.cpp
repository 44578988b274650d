#include "mesh/mesh.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/error.hpp"

namespace stiction::mesh {

std::array<int, 2> simplex_edge(int d, int e) {
  switch (d) {
    case 1: return SimplexEdges<1>::list[e];
    case 2: return SimplexEdges<2>::list[e];
    case 3: return SimplexEdges<3>::list[e];
  }
  throw Error(fmt::format("simplex_edge: unsupported dimension {}", d), ErrorKind::Internal);
}

int EdgeTopology::find(int a, int b) const {
  const std::array<int, 2> key{std::min(a, b), std::max(a, b)};
  auto it = std::lower_bound(edges.begin(), edges.end(), key);
  return (it != edges.end() && *it == key) ? static_cast<int>(it - edges.begin()) : -1;
}

EdgeTopology build_edges(const Mesh& mesh) {
  const int d = mesh.dim, nve = n_simplex_edges(d), nc = mesh.n_cells();
  // (lo, hi, slot) triples sorted by vertex pair; slot = cell * nve + local edge.
  struct Entry {
    int lo, hi, slot;
  };
  std::vector<Entry> all;
  all.reserve(static_cast<size_t>(nc) * nve);
  for (int c = 0; c < nc; ++c) {
    const int* v = mesh.cell(c);
    for (int e = 0; e < nve; ++e) {
      auto [i, j] = simplex_edge(d, e);
      all.push_back({std::min(v[i], v[j]), std::max(v[i], v[j]), c * nve + e});
    }
  }
  std::sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) {
    return a.lo != b.lo ? a.lo < b.lo : a.hi < b.hi;
  });
  EdgeTopology topo;
  topo.cell_edges.assign(all.size(), -1);
  for (size_t k = 0; k < all.size(); ++k) {
    if (k == 0 || all[k].lo != all[k - 1].lo || all[k].hi != all[k - 1].hi)
      topo.edges.push_back({all[k].lo, all[k].hi});
    topo.cell_edges[all[k].slot] = topo.n_edges() - 1;
  }
  const int nfe = n_simplex_edges(d - 1);
  topo.facet_edges.resize(static_cast<size_t>(mesh.n_facets()) * nfe);
  for (int f = 0; f < mesh.n_facets(); ++f) {
    const int* v = mesh.facet(f);
    for (int e = 0; e < nfe; ++e) {
      auto [i, j] = simplex_edge(d - 1, e);
      const int id = topo.find(v[i], v[j]);
      if (id < 0)
        throw Error(fmt::format("mesh: boundary facet {} is not a face of any cell", f));
      topo.facet_edges[static_cast<size_t>(f) * nfe + e] = id;
    }
  }
  return topo;
}

double signed_measure(const Mesh& mesh, int cell) {
  const int* v = mesh.cell(cell);
  const double* x0 = mesh.vertex(v[0]);
  if (mesh.dim == 2) {
    const double* x1 = mesh.vertex(v[1]);
    const double* x2 = mesh.vertex(v[2]);
    return 0.5 * ((x1[0] - x0[0]) * (x2[1] - x0[1]) - (x1[1] - x0[1]) * (x2[0] - x0[0]));
  }
  double a[3], b[3], c[3];
  for (int k = 0; k < 3; ++k) {
    a[k] = mesh.vertex(v[1])[k] - x0[k];
    b[k] = mesh.vertex(v[2])[k] - x0[k];
    c[k] = mesh.vertex(v[3])[k] - x0[k];
  }
  return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
}

void Mesh::edge_offset(int a, int b, double* out) const {
  std::fill(out, out + dim, 0.0);
  const auto it = edge_midpoints.find({std::min(a, b), std::max(a, b)});
  if (it == edge_midpoints.end()) return;
  for (int k = 0; k < dim; ++k) out[k] = it->second[k] - 0.5 * (vertex(a)[k] + vertex(b)[k]);
}

void Mesh::set_edge_midpoint(int a, int b, const double* mid) {
  double gap = 0, length = 0;
  for (int k = 0; k < dim; ++k) {
    gap += std::pow(mid[k] - 0.5 * (vertex(a)[k] + vertex(b)[k]), 2);
    length += std::pow(vertex(a)[k] - vertex(b)[k], 2);
  }
  if (!(gap > 1e-24 * length)) return;
  std::array<double, 3> point{0, 0, 0};
  std::copy(mid, mid + dim, point.begin());
  edge_midpoints[{std::min(a, b), std::max(a, b)}] = point;
}

void curved_cell_map(const Mesh& mesh, int cell, const double* l, double* X, double* det) {
  const int d = mesh.dim;
  const int* v = mesh.cell(cell);
  // dl_v / dxi_j with xi_j = l_{j+1}, l_0 = 1 - sum xi.
  auto dl = [](int vtx, int j) { return (vtx == j + 1 ? 1.0 : 0.0) - (vtx == 0 ? 1.0 : 0.0); };
  double J[3][3] = {};
  std::fill(X, X + d, 0.0);
  for (int k = 0; k <= d; ++k)
    for (int i = 0; i < d; ++i) {
      X[i] += mesh.vertex(v[k])[i] * l[k];
      for (int j = 0; j < d; ++j) J[i][j] += mesh.vertex(v[k])[i] * dl(k, j);
    }
  double offset[3];
  for (int e = 0; e < n_simplex_edges(d); ++e) {
    const auto [a, b] = simplex_edge(d, e);
    mesh.edge_offset(v[a], v[b], offset);
    for (int i = 0; i < d; ++i) {
      X[i] += offset[i] * 4 * l[a] * l[b];
      for (int j = 0; j < d; ++j) J[i][j] += offset[i] * 4 * (dl(a, j) * l[b] + l[a] * dl(b, j));
    }
  }
  *det = d == 2 ? J[0][0] * J[1][1] - J[0][1] * J[1][0]
                : J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                      J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

namespace {

bool has_curved_edge(const Mesh& mesh, int c) {
  const int* v = mesh.cell(c);
  for (int e = 0; e < n_simplex_edges(mesh.dim); ++e) {
    const auto [a, b] = simplex_edge(mesh.dim, e);
    if (mesh.edge_midpoints.count({std::min(v[a], v[b]), std::max(v[a], v[b])})) return true;
  }
  return false;
}

// Barycentric coordinates of a cell's nodes: its vertices, then its edge midpoints.
std::vector<std::array<double, 4>> node_barycentrics(int d) {
  std::vector<std::array<double, 4>> out(d + 1, {0, 0, 0, 0});
  for (int k = 0; k <= d; ++k) out[k][k] = 1;
  for (int e = 0; e < n_simplex_edges(d); ++e) {
    const auto [a, b] = simplex_edge(d, e);
    std::array<double, 4> l{0, 0, 0, 0};
    l[a] = l[b] = 0.5;
    out.push_back(l);
  }
  return out;
}

}  // namespace

double bounding_diagonal(const Mesh& mesh) {
  double sq = 0;
  for (int k = 0; k < mesh.dim; ++k) {
    double lo = INFINITY, hi = -INFINITY;
    for (int v = 0; v < mesh.n_vertices(); ++v) {
      lo = std::min(lo, mesh.vertex(v)[k]);
      hi = std::max(hi, mesh.vertex(v)[k]);
    }
    if (mesh.n_vertices() > 0) sq += (hi - lo) * (hi - lo);
  }
  return std::sqrt(sq);
}

void check_validity(const Mesh& mesh, const std::string& what) {
  if (mesh.dim != 2 && mesh.dim != 3)
    throw Error(fmt::format("{}: unsupported mesh dimension {} (2 or 3 expected)", what, mesh.dim));
  if (mesh.n_cells() == 0) throw Error(fmt::format("{}: the mesh has no cells", what));
  for (int c : mesh.cells)
    if (c < 0 || c >= mesh.n_vertices())
      throw Error(fmt::format("{}: cell refers to vertex {} out of range", what, c));
  // Degenerate: measure below a tiny fraction of the mesh's typical cell measure.
  const double typical = std::pow(bounding_diagonal(mesh), mesh.dim) / mesh.n_cells();
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const double m = signed_measure(mesh, c);
    if (m > 1e-12 * typical) continue;
    std::string xs;
    for (int k = 0; k <= mesh.dim; ++k) {
      const double* x = mesh.vertex(mesh.cell(c)[k]);
      xs += mesh.dim == 2 ? fmt::format(" ({:g}, {:g})", x[0], x[1])
                          : fmt::format(" ({:g}, {:g}, {:g})", x[0], x[1], x[2]);
    }
    throw Error(fmt::format("{}: {} element {} (signed measure {:.3g}) with vertices{}", what,
                            m < 0 ? "inverted" : "degenerate", c, m, xs));
  }
  if (!mesh.is_curved()) return;
  const auto nodes = node_barycentrics(mesh.dim);
  double X[3], det;
  for (int c = 0; c < mesh.n_cells(); ++c) {
    if (!has_curved_edge(mesh, c)) continue;
    for (const auto& l : nodes) {
      curved_cell_map(mesh, c, l.data(), X, &det);
      if (!(det > 0))
        throw Error(fmt::format("{}: curved {} is folded: det(dX/dxi) = {:.3g} at one of its nodes (an edge "
                                "midpoint on the geometry lies too far from the chord for the cell's size)",
                                what, describe_cell(mesh, c), det));
    }
  }
}

std::string describe_cell(const Mesh& mesh, int c) {
  std::array<double, 3> centroid{};
  for (int k = 0; k < mesh.vertices_per_cell(); ++k)
    for (int i = 0; i < mesh.dim; ++i) centroid[i] += mesh.vertex(mesh.cell(c)[k])[i] / mesh.vertices_per_cell();
  return fmt::format("cell {} (vertex centroid ({:.4g}))", c,
                     fmt::join(centroid.begin(), centroid.begin() + mesh.dim, ", "));
}

namespace {

// Children of a triangle (v0 v1 v2) with edge midpoints m01 m12 m20: same orientation.
void split_triangle(const int* v, const int* m /* 01 12 20 */, std::vector<int>& out) {
  const int kids[4][3] = {{v[0], m[0], m[2]}, {m[0], v[1], m[1]}, {m[2], m[1], v[2]}, {m[0], m[1], m[2]}};
  for (auto& k : kids) out.insert(out.end(), k, k + 3);
}

double dist2(const Mesh& mesh, int a, int b) {
  double s = 0;
  for (int k = 0; k < mesh.dim; ++k) s += std::pow(mesh.vertex(a)[k] - mesh.vertex(b)[k], 2);
  return s;
}

// The curved edges of parent cell c's children (the last `children` cells of fine): each
// child edge's midpoint is the parent's quadratic map at the edge's middle (kept where it
// leaves the child's chord: Mesh::set_edge_midpoint). m holds the fine vertices at the
// parent's edge midpoints.
void add_children_curves(const Mesh& mesh, int c, const int* m, int children, Mesh& fine) {
  const int d = mesh.dim, nve = n_simplex_edges(d);
  const int* v = mesh.cell(c);
  const auto nodes = node_barycentrics(d);
  std::map<int, std::array<double, 4>> bary;  // fine vertex -> barycentric coordinates in c
  for (int k = 0; k <= d; ++k) bary[v[k]] = nodes[k];
  for (int e = 0; e < nve; ++e) bary[m[e]] = nodes[d + 1 + e];
  double X[3], det;
  for (int child = fine.n_cells() - children; child < fine.n_cells(); ++child) {
    const int* w = fine.cell(child);
    for (int e = 0; e < nve; ++e) {
      const auto [a, b] = simplex_edge(d, e);
      std::array<double, 4> l{};
      for (int k = 0; k <= d; ++k) l[k] = 0.5 * (bary.at(w[a])[k] + bary.at(w[b])[k]);
      curved_cell_map(mesh, c, l.data(), X, &det);
      fine.set_edge_midpoint(w[a], w[b], X);
    }
  }
}

}  // namespace

Mesh refine(const Mesh& mesh) {
  const EdgeTopology topo = build_edges(mesh);
  const int nv = mesh.n_vertices(), d = mesh.dim, nve = n_simplex_edges(d);
  Mesh fine;
  fine.dim = d;
  fine.cell_tag_names = mesh.cell_tag_names;
  fine.facet_tag_names = mesh.facet_tag_names;
  fine.coords = mesh.coords;
  fine.coords.reserve(static_cast<size_t>(nv + topo.n_edges()) * d);
  double offset[3];
  for (auto [a, b] : topo.edges) {
    mesh.edge_offset(a, b, offset);
    for (int k = 0; k < d; ++k) fine.coords.push_back(0.5 * (mesh.vertex(a)[k] + mesh.vertex(b)[k]) + offset[k]);
  }

  const int children = d == 2 ? 4 : 8;
  fine.cells.reserve(mesh.cells.size() * children);
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const int* v = mesh.cell(c);
    int m[6];
    for (int e = 0; e < nve; ++e) m[e] = nv + topo.cell_edges[static_cast<size_t>(c) * nve + e];
    if (d == 2) {
      split_triangle(v, m, fine.cells);
    } else {
      // VTK edge order: m[0]=01 m[1]=12 m[2]=20 m[3]=03 m[4]=13 m[5]=23.
      const int m01 = m[0], m12 = m[1], m02 = m[2], m03 = m[3], m13 = m[4], m23 = m[5];
      const int corners[4][4] = {{v[0], m01, m02, m03}, {m01, v[1], m12, m13},
                                 {m02, m12, v[2], m23}, {m03, m13, m23, v[3]}};
      for (auto& k : corners) fine.cells.insert(fine.cells.end(), k, k + 4);
      // Interior octahedron: split along the shortest of its three diagonals (opposite
      // midpoint pairs); the other four vertices form a cycle c, e, d, f around it.
      const int diag[3][2] = {{m01, m23}, {m02, m13}, {m03, m12}};
      int best = 0;
      for (int k = 1; k < 3; ++k)
        if (dist2(fine, diag[k][0], diag[k][1]) < dist2(fine, diag[best][0], diag[best][1]) - 1e-14)
          best = k;
      const int* o1 = diag[(best + 1) % 3];
      const int* o2 = diag[(best + 2) % 3];
      const int ring[4] = {o1[0], o2[0], o1[1], o2[1]};
      for (int k = 0; k < 4; ++k) {
        const int tet[4] = {diag[best][0], diag[best][1], ring[k], ring[(k + 1) % 4]};
        fine.cells.insert(fine.cells.end(), tet, tet + 4);
      }
    }
    fine.cell_tags.insert(fine.cell_tags.end(), children, mesh.cell_tags[c]);
    if (mesh.is_curved() && has_curved_edge(mesh, c)) add_children_curves(mesh, c, m, children, fine);
  }
  // Fix the orientation of the interior tetrahedra (corner children keep the parent's).
  for (int c = 0; c < fine.n_cells(); ++c)
    if (signed_measure(fine, c) < 0) std::swap(fine.cells[static_cast<size_t>(c) * 4 + 2], fine.cells[static_cast<size_t>(c) * 4 + 3]);

  const int nfe = n_simplex_edges(d - 1);
  for (int f = 0; f < mesh.n_facets(); ++f) {
    const int* v = mesh.facet(f);
    int m[3];
    for (int e = 0; e < nfe; ++e) m[e] = nv + topo.facet_edges[static_cast<size_t>(f) * nfe + e];
    if (d == 2) {
      const int segs[4] = {v[0], m[0], m[0], v[1]};
      fine.facets.insert(fine.facets.end(), segs, segs + 4);
      fine.facet_tags.insert(fine.facet_tags.end(), 2, mesh.facet_tags[f]);
    } else {
      split_triangle(v, m, fine.facets);
      fine.facet_tags.insert(fine.facet_tags.end(), 4, mesh.facet_tags[f]);
    }
  }
  return fine;
}

Mesh refine(const Mesh& mesh, int levels) {
  Mesh m = mesh;
  for (int k = 0; k < levels; ++k) m = refine(m);
  return m;
}

TagOffsets append(Mesh& into, const Mesh& part, const std::string& prefix) {
  if (into.dim == 0) into.dim = part.dim;
  if (into.dim != part.dim)
    throw Error(fmt::format("bodies of different dimensions ({} and {}) in one scene", into.dim, part.dim));
  TagOffsets off;
  for (int t : into.cell_tags) off.cell = std::max(off.cell, t);
  for (int t : into.facet_tags) off.facet = std::max(off.facet, t);
  for (auto& [n, t] : into.cell_tag_names) off.cell = std::max(off.cell, t);
  for (auto& [n, t] : into.facet_tag_names) off.facet = std::max(off.facet, t);
  const int nv = into.n_vertices();
  into.coords.insert(into.coords.end(), part.coords.begin(), part.coords.end());
  for (int v : part.cells) into.cells.push_back(v + nv);
  for (int v : part.facets) into.facets.push_back(v + nv);
  for (int t : part.cell_tags) into.cell_tags.push_back(t + off.cell);
  for (int t : part.facet_tags) into.facet_tags.push_back(t + off.facet);
  for (auto& [n, t] : part.cell_tag_names) into.cell_tag_names[prefix + "/" + n] = t + off.cell;
  for (auto& [n, t] : part.facet_tag_names) into.facet_tag_names[prefix + "/" + n] = t + off.facet;
  for (const auto& [edge, mid] : part.edge_midpoints) into.edge_midpoints[{edge[0] + nv, edge[1] + nv}] = mid;
  return off;
}

namespace {

// Boundary facets (faces of exactly one cell), each oriented as a face of its cell.
std::vector<std::vector<int>> boundary_faces(const Mesh& mesh) {
  const int d = mesh.dim;
  std::vector<std::pair<std::vector<int>, std::vector<int>>> faces;  // (sorted key, face)
  for (int c = 0; c < mesh.n_cells(); ++c)
    for (int skip = 0; skip <= d; ++skip) {
      std::vector<int> f;
      for (int k = 0; k <= d; ++k)
        if (k != skip) f.push_back(mesh.cell(c)[k]);
      auto key = f;
      std::sort(key.begin(), key.end());
      faces.emplace_back(std::move(key), std::move(f));
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::vector<int>> out;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i;
    while (j < faces.size() && faces[j].first == faces[i].first) ++j;
    if (j - i == 1) out.push_back(faces[i].second);
    i = j;
  }
  return out;
}

}  // namespace

Mesh structured_box(int dim, const std::array<double, 3>& L, const std::array<int, 3>& n) {
  Mesh m;
  m.dim = dim;
  const int nx = n[0], ny = n[1], nz = dim == 3 ? n[2] : 0;
  auto vid = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        m.coords.push_back(L[0] * i / nx);
        m.coords.push_back(L[1] * j / ny);
        if (dim == 3) m.coords.push_back(L[2] * k / nz);
      }
  if (dim == 2) {
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int a = vid(i, j, 0), b = vid(i + 1, j, 0), c = vid(i + 1, j + 1, 0), d = vid(i, j + 1, 0);
        for (int v : {a, b, c, a, c, d}) m.cells.push_back(v);
      }
  } else {
    // Kuhn subdivision: 6 tetrahedra sharing the cube diagonal, conforming across cubes.
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i)
          for (auto& p : perms) {
            int ijk[3] = {i, j, k};
            m.cells.push_back(vid(ijk[0], ijk[1], ijk[2]));
            for (int s = 0; s < 3; ++s) {
              ++ijk[p[s]];
              m.cells.push_back(vid(ijk[0], ijk[1], ijk[2]));
            }
          }
  }
  m.cell_tags.assign(m.n_cells(), 1);
  for (int c = 0; c < m.n_cells(); ++c)
    if (signed_measure(m, c) < 0) std::swap(m.cells[static_cast<size_t>(c) * (dim + 1)], m.cells[static_cast<size_t>(c) * (dim + 1) + 1]);
  m.cell_tag_names["body"] = 1;
  const char* names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  for (int t = 0; t < 2 * dim; ++t) m.facet_tag_names[names[t]] = t + 1;
  for (auto& f : boundary_faces(m)) {
    for (int axis = 0; axis < dim; ++axis) {
      bool lo = true, hi = true;
      for (int v : f) {
        lo = lo && std::abs(m.vertex(v)[axis]) < 1e-12 * L[axis];
        hi = hi && std::abs(m.vertex(v)[axis] - L[axis]) < 1e-12 * L[axis];
      }
      if (lo || hi) {
        m.facets.insert(m.facets.end(), f.begin(), f.end());
        m.facet_tags.push_back(2 * axis + (hi ? 2 : 1));
        break;
      }
    }
  }
  return m;
}

std::array<int, 3> facet_key(const int* v, int n) {
  std::array<int, 3> key{-1, -1, -1};
  std::copy(v, v + n, key.end() - n);
  std::sort(key.begin(), key.end());
  return key;
}

std::vector<std::array<int, 3>> cell_facet_keys(const int* v, int dim) {
  std::vector<std::array<int, 3>> keys;
  for (int skip = 0; skip <= dim; ++skip) {
    std::array<int, 3> face{};
    int k = 0;
    for (int i = 0; i <= dim; ++i)
      if (i != skip) face[k++] = v[i];
    keys.push_back(facet_key(face.data(), dim));
  }
  return keys;
}

}  // namespace stiction::mesh
