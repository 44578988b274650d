#include "mesh/gmsh_session.hpp"

#include <gmsh.h>

#include <array>
#include <cmath>
#include <functional>
#include <unordered_map>
#include <vector>

namespace stiction::mesh::detail {

// Gmsh keeps one global model: initialise it once, start each use from an empty model.
void gmsh_begin() {
  static bool initialised = false;
  if (!initialised) {
    gmsh::initialize(0, nullptr, false);
    initialised = true;
  }
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::option::setNumber("General.Verbosity", 1);
  gmsh::option::setNumber("General.NumThreads", 1);  // deterministic meshes
  // Options outlive the model: reset the ones a generator changes to Gmsh's defaults, or a
  // sphere octant (sizes from its field only) left every later polygon in the process
  // meshed at uniform h, its point sizes ignored.
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 1);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFactor", 1);
  gmsh::clear();
}

std::string gmsh_last_error() {
  std::string e;
  try {
    gmsh::logger::getLastError(e);
  } catch (...) {
  }
  return e;
}

Mesh extract_current_model(const std::string& what) {
  Mesh m;
  m.dim = gmsh::model::getDimension();
  if (m.dim != 2 && m.dim != 3)
    throw Error(fmt::format("{}: mesh of dimension {} (2 or 3 expected)", what, m.dim));
  const int d = m.dim;

  std::vector<std::size_t> node_tags;
  std::vector<double> xyz, param;
  gmsh::model::mesh::getNodes(node_tags, xyz, param, -1, -1, false, false);
  std::unordered_map<std::size_t, int> local;  // gmsh node tag -> vertex index
  std::unordered_map<std::size_t, size_t> pos;  // gmsh node tag -> position in xyz
  for (size_t i = 0; i < node_tags.size(); ++i) pos[node_tags[i]] = i;
  auto vertex_of = [&](std::size_t tag) {
    auto it = local.find(tag);
    if (it != local.end()) return it->second;
    auto p = pos.find(tag);
    if (p == pos.end()) throw Error(fmt::format("{}: element refers to unknown node {}", what, tag));
    const int id = m.n_vertices();
    for (int k = 0; k < d; ++k) m.coords.push_back(xyz[3 * p->second + k]);
    local[tag] = id;
    return id;
  };

  // Calls f(node tags, edge of each high-order node) for each simplex of dimension `dim` in
  // entity `entity`: the corners first; a second-order element's further nodes lie on its
  // edges, edge_of[k] naming the pair of corners (from their reference coordinates).
  using EdgeOfNode = std::vector<std::array<int, 2>>;
  auto for_simplices = [&](int dim, int entity, const std::function<void(const std::size_t*, const EdgeOfNode&)>& f) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, dim, entity);
    for (size_t t = 0; t < types.size(); ++t) {
      std::string name;
      int edim, order, n_nodes, n_primary;
      std::vector<double> local_coords;
      gmsh::model::mesh::getElementProperties(types[t], name, edim, order, n_nodes, local_coords, n_primary);
      if (n_primary != dim + 1)
        throw Error(fmt::format("{}: element type '{}' is not a simplex (only triangles and "
                                "tetrahedra are supported)", what, name));
      EdgeOfNode edge_of;
      if (order == 2)
        for (int k = n_primary; k < n_nodes; ++k) {
          std::array<int, 2> found{-1, -1};
          for (int a = 0; a < n_primary; ++a)
            for (int b = a + 1; b < n_primary; ++b) {
              double miss = 0;
              for (int i = 0; i < edim; ++i)  // edim coordinates per node
                miss += std::abs(local_coords[edim * k + i] - 0.5 * (local_coords[edim * a + i] + local_coords[edim * b + i]));
              if (miss < 1e-9) found = {a, b};
            }
          edge_of.push_back(found);
        }
      for (size_t e = 0; e < tags[t].size(); ++e) f(&nodes[t][e * n_nodes], edge_of);
    }
  };

  // A second-order node off its edge's chord is a curved edge's midpoint (Mesh::edge_midpoints).
  auto record_curved_edges = [&](const std::size_t* n, const EdgeOfNode& edge_of) {
    for (size_t k = 0; k < edge_of.size(); ++k) {
      const auto [a, b] = edge_of[k];
      if (a < 0) continue;
      m.set_edge_midpoint(local.at(n[a]), local.at(n[b]), &xyz[3 * pos.at(n[d + 1 + k])]);
    }
  };

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, d);
  auto add_cells = [&](int entity, int tag) {
    for_simplices(d, entity, [&](const std::size_t* n, const EdgeOfNode& edge_of) {
      for (int k = 0; k <= d; ++k) m.cells.push_back(vertex_of(n[k]));
      m.cell_tags.push_back(tag);
      record_curved_edges(n, edge_of);
    });
  };
  if (groups.empty()) {
    add_cells(-1, 1);
    m.cell_tag_names["body"] = 1;
  }
  for (auto [gd, gtag] : groups) {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(gd, gtag, entities);
    for (int e : entities) add_cells(e, gtag);
    std::string name;
    gmsh::model::getPhysicalName(gd, gtag, name);
    m.cell_tag_names[name.empty() ? std::to_string(gtag) : name] = gtag;
  }
  if (m.n_cells() == 0) throw Error(fmt::format("{}: no {}D cells found", what, d));

  gmsh::vectorpair fgroups;
  gmsh::model::getPhysicalGroups(fgroups, d - 1);
  for (auto [gd, gtag] : fgroups) {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(gd, gtag, entities);
    for (int e : entities)
      for_simplices(d - 1, e, [&](const std::size_t* n, const EdgeOfNode&) {
        for (int k = 0; k < d; ++k) {
          auto it = local.find(n[k]);
          if (it == local.end())
            throw Error(fmt::format("{}: boundary group {} has a node on no cell", what, gtag));
          m.facets.push_back(it->second);
        }
        m.facet_tags.push_back(gtag);
      });
    std::string name;
    gmsh::model::getPhysicalName(gd, gtag, name);
    m.facet_tag_names[name.empty() ? std::to_string(gtag) : name] = gtag;
  }
  return m;
}

void place_edge_midpoints_on_geometry() {
  bool curved = false;
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities);
  for (auto [dim, tag] : entities) {
    if (dim != 1 && dim != 2) continue;
    std::string type;
    gmsh::model::getType(dim, tag, type);
    curved = curved || (dim == 1 ? type != "Line" : type != "Plane");
  }
  if (!curved) return;
  gmsh::option::setNumber("Mesh.SecondOrderLinear", 0);  // the new nodes on the CAD entities
  gmsh::model::mesh::setOrder(2);
}

void set_size_and_generate(int dim, double h, double h_min) {
  gmsh::option::setNumber("Mesh.MeshSizeMin", h_min > 0 ? h_min : h);
  gmsh::option::setNumber("Mesh.MeshSizeMax", h);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay: fast and deterministic
  gmsh::model::mesh::generate(dim);
  place_edge_midpoints_on_geometry();
}

}  // namespace stiction::mesh::detail
