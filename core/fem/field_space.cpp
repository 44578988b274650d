#include "fem/field_space.hpp"

namespace stiction::fem {

FieldSpace::FieldSpace(const mesh::Mesh& mesh, BasisKind kind, const std::vector<char>& vertex_has_pressure)
    : mesh_(&mesh), kind_(kind), topo_(mesh::build_edges(mesh)) {
  if (is_quadratic(kind) && mesh.is_curved()) {
    const int d = mesh.dim, ne = mesh::n_simplex_edges(d);
    edge_offset_.assign(static_cast<size_t>(topo_.n_edges()) * d, 0.0);
    std::vector<char> curved_edge(topo_.n_edges(), 0);
    for (const auto& [edge, mid] : mesh.edge_midpoints) {
      const int e = topo_.find(edge[0], edge[1]);
      if (e < 0) continue;  // not an edge of any cell
      mesh.edge_offset(edge[0], edge[1], &edge_offset_[static_cast<size_t>(e) * d]);
      curved_edge[e] = 1;
    }
    curved_cell_.assign(mesh.n_cells(), 0);
    for (int c = 0; c < mesh.n_cells(); ++c)
      for (int k = 0; k < ne; ++k) curved_cell_[c] |= curved_edge[topo_.cell_edges[static_cast<size_t>(c) * ne + k]];
  }
  if (vertex_has_pressure.empty()) return;
  pressure_index_.assign(mesh.n_vertices(), -1);
  for (int v = 0; v < mesh.n_vertices(); ++v)
    if (vertex_has_pressure[v]) pressure_index_[v] = n_pressure_++;
}

void FieldSpace::cell_nodes(int cell, int* nodes) const {
  const int d = dim(), nv = d + 1;
  const int* v = mesh_->cell(cell);
  for (int k = 0; k < nv; ++k) nodes[k] = v[k];
  if (!is_quadratic(kind_)) return;
  const int ne = mesh::n_simplex_edges(d);
  for (int e = 0; e < ne; ++e) nodes[nv + e] = n_vertices() + topo_.cell_edges[static_cast<size_t>(cell) * ne + e];
}

void FieldSpace::facet_nodes(int facet, int* nodes) const {
  const int d = dim();
  const int* v = mesh_->facet(facet);
  for (int k = 0; k < d; ++k) nodes[k] = v[k];
  if (!is_quadratic(kind_)) return;
  const int ne = mesh::n_simplex_edges(d - 1);
  for (int e = 0; e < ne; ++e) nodes[d + e] = n_vertices() + topo_.facet_edges[static_cast<size_t>(facet) * ne + e];
}

void FieldSpace::node_position(int node, double* X) const {
  const int d = dim();
  if (is_vertex_node(node)) {
    for (int k = 0; k < d; ++k) X[k] = mesh_->vertex(node)[k];
    return;
  }
  const auto [a, b] = topo_.edges[node - n_vertices()];
  const double* offset = node_offset(node);
  for (int k = 0; k < d; ++k) X[k] = 0.5 * (mesh_->vertex(a)[k] + mesh_->vertex(b)[k]) + offset[k];
}

void FieldSpace::interpolate(const VectorField& g, std::vector<double>& coefs) const {
  const int d = dim();
  coefs.assign(n_dofs(), 0.0);
  double X[3];
  for (int n = 0; n < n_nodes(); ++n) {
    node_position(n, X);
    g(X, &coefs[static_cast<size_t>(n) * d]);
  }  // pressure entries stay zero
  if (kind_ != BasisKind::P2Hierarchical) return;
  for (int e = 0; e < topo_.n_edges(); ++e) {
    const auto [a, b] = topo_.edges[e];
    double* c = &coefs[static_cast<size_t>(n_vertices() + e) * d];
    for (int k = 0; k < d; ++k) c[k] -= 0.5 * (coefs[static_cast<size_t>(a) * d + k] + coefs[static_cast<size_t>(b) * d + k]);
  }
}

void FieldSpace::interpolate_node(const VectorField& g, int node, double* out) const {
  double X[3];
  node_position(node, X);
  g(X, out);
  if (is_vertex_node(node) || kind_ != BasisKind::P2Hierarchical) return;
  const auto [a, b] = topo_.edges[node - n_vertices()];
  double ga[3], gb[3];
  g(mesh_->vertex(a), ga);
  g(mesh_->vertex(b), gb);
  for (int k = 0; k < dim(); ++k) out[k] -= 0.5 * (ga[k] + gb[k]);
}

double FieldSpace::nodal_pressure(StateView coefs, int node) const {
  if (is_vertex_node(node)) return pressure_dof(node) >= 0 ? coefs[pressure_dof(node)] : 0.0;
  const auto [a, b] = topo_.edges[node - n_vertices()];
  return 0.5 * (nodal_pressure(coefs, a) + nodal_pressure(coefs, b));
}

void FieldSpace::nodal_value(StateView coefs, int node, double* out) const {
  const int d = dim();
  for (int k = 0; k < d; ++k) out[k] = coefs[static_cast<size_t>(node) * d + k];
  if (kind_ != BasisKind::P2Hierarchical || is_vertex_node(node)) return;
  const auto [a, b] = topo_.edges[node - n_vertices()];
  for (int k = 0; k < d; ++k) out[k] += 0.5 * (coefs[static_cast<size_t>(a) * d + k] + coefs[static_cast<size_t>(b) * d + k]);
}

std::vector<double> FieldSpace::nodal_pressure(const std::vector<double>& coefs) const {
  std::vector<double> out(n_nodes());
  for (int n = 0; n < n_nodes(); ++n) out[n] = nodal_pressure(StateView(coefs), n);
  return out;
}

std::vector<double> FieldSpace::nodal_values(const std::vector<double>& coefs) const {
  std::vector<double> out(static_cast<size_t>(n_displacement_dofs()));
  const int d = dim();
  for (int n = 0; n < n_nodes(); ++n) nodal_value(coefs, n, &out[static_cast<size_t>(n) * d]);
  return out;
}

}  // namespace stiction::fem
