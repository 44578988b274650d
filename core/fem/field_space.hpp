#pragma once
// The unknowns of a problem on a simplicial mesh: a vector-valued P1 or P2 displacement
// and, on bodies with a mixed (displacement-pressure) law, a continuous P1 pressure
// (Taylor-Hood P2-P1, paper Sec. 2.3).
//
// Nodes: mesh vertices first, then (P2) one node per edge, so node n = n_vertices + edge.
// Displacement dofs: dof = node * dim + component. The P2 space therefore splits into
// field blocks [u_l | u_q] = [vertex dofs | edge dofs], contiguous ranges of the global
// vector, both with block size dim. With the hierarchical basis the u_l coefficients are
// the P1 solution's nodal values and the u_q coefficients the edge corrections; with the
// nodal basis the edge coefficients are midpoint values. Pressure dofs follow as the last
// block [p], one per vertex of a mixed body, in vertex order.
#include <functional>
#include <vector>

#include "fem/app_view.hpp"
#include "fem/basis.hpp"
#include "mesh/mesh.hpp"

namespace stiction::fem {

// g(X, out): a vector field on the reference configuration (out has dim entries).
using VectorField = std::function<void(const double* X, double* out)>;

class FieldSpace {
public:
  // vertex_has_pressure (empty: no pressure field) marks the vertices of mixed bodies.
  FieldSpace(const mesh::Mesh& mesh, BasisKind kind, const std::vector<char>& vertex_has_pressure = {});

  const mesh::Mesh& mesh() const { return *mesh_; }
  const mesh::EdgeTopology& edges() const { return topo_; }
  BasisKind kind() const { return kind_; }
  int dim() const { return mesh_->dim; }
  int n_vertices() const { return mesh_->n_vertices(); }
  int n_nodes() const { return n_vertices() + (is_quadratic(kind_) ? topo_.n_edges() : 0); }
  int n_displacement_dofs() const { return n_nodes() * dim(); }
  int n_pressure_dofs() const { return n_pressure_; }
  int n_dofs() const { return n_displacement_dofs() + n_pressure_; }
  bool has_pressure() const { return n_pressure_ > 0; }
  // Global dof of the pressure at a vertex, or -1 (vertex of a displacement-only body).
  int pressure_dof(int vertex) const {
    return pressure_index_.empty() || pressure_index_[vertex] < 0 ? -1 : n_displacement_dofs() + pressure_index_[vertex];
  }
  int nodes_per_cell() const { return n_shape_functions(dim(), kind_); }
  int nodes_per_facet() const { return n_shape_functions(dim() - 1, kind_); }

  // Field blocks as half-open dof ranges: u_l = vertex dofs, u_q = edge dofs (empty for P1).
  std::pair<int, int> linear_block() const { return {0, n_vertices() * dim()}; }
  std::pair<int, int> quadratic_block() const { return {n_vertices() * dim(), n_displacement_dofs()}; }
  std::pair<int, int> pressure_block() const { return {n_displacement_dofs(), n_dofs()}; }

  void cell_nodes(int cell, int* nodes) const;    // local order: vertices, edges
  void facet_nodes(int facet, int* nodes) const;
  bool is_vertex_node(int node) const { return node < n_vertices(); }
  // Position of a node in the reference configuration (vertex, or edge midpoint: on the
  // geometry where the edge is curved).
  void node_position(int node, double* X) const;
  // Isoparametric geometry: P2 cells map through their edge nodes, X(xi) = chord map +
  // sum over edge nodes of node_offset * N_edge(xi) (fem/cell_geometry.hpp). The offset of a
  // node is true midpoint - chord midpoint (dim entries): zero at vertices, on straight
  // edges and in P1 spaces, which keep the chords.
  bool is_curved() const { return !edge_offset_.empty(); }
  bool is_curved_cell(int cell) const { return !curved_cell_.empty() && curved_cell_[cell]; }
  const double* node_offset(int node) const {
    return is_curved() && !is_vertex_node(node) ? &edge_offset_[static_cast<size_t>(node - n_vertices()) * dim()] : kZero;
  }

  // Coefficients of the displacement interpolant of g, written into coefs (size n_dofs,
  // pressure entries zero). Hierarchical edge coefficient: g(mid) - (g(a) + g(b)) / 2.
  void interpolate(const VectorField& g, std::vector<double>& coefs) const;
  // The same coefficient for one node (dim entries into out).
  void interpolate_node(const VectorField& g, int node, double* out) const;
  // Nodal displacement values (vertices, then edge midpoints) of a coefficient vector.
  std::vector<double> nodal_values(const std::vector<double>& coefs) const;
  // Pressure at every node (P1: vertex value, edge midpoint = mean of its vertices; 0 where
  // there is no pressure field).
  std::vector<double> nodal_pressure(const std::vector<double>& coefs) const;
  // The same at one node (dim entries into out), from coefficients of which the node's
  // and, at an edge node, its edge's vertices' are held (a process's ghosted storage).
  void nodal_value(StateView coefs, int node, double* out) const;
  double nodal_pressure(StateView coefs, int node) const;
  // Coefficient weights w with sum_i w_i r_i = total force for a nodal force vector r:
  // the coefficients of the constant 1 (1 on vertices; on edges 1 nodal, 0 hierarchical).
  double unit_weight(int node) const { return is_vertex_node(node) || kind_ == BasisKind::P2Nodal ? 1.0 : 0.0; }

private:
  const mesh::Mesh* mesh_;
  BasisKind kind_;
  mesh::EdgeTopology topo_;
  std::vector<int> pressure_index_;  // per vertex, -1 without pressure
  std::vector<double> edge_offset_;  // n_edges x dim; empty when no edge is curved
  std::vector<char> curved_cell_;    // per cell: one of its edges is curved
  static constexpr double kZero[3] = {0, 0, 0};
  int n_pressure_ = 0;
};

}  // namespace stiction::fem
