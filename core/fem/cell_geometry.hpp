#pragma once
// The map of the reference simplex onto a cell or a boundary facet: the chord (affine) map
// from the vertices plus, on curved P2 cells, the isoparametric term over the edge nodes,
//   X(xi) = X_0 + E xi + sum over edge nodes a of g_a N_a(xi),
// g_a = FieldSpace::node_offset (true midpoint - chord midpoint). Both P2 bases share the
// edge function 4 l_a l_b, so N_a and dN_a are the space's own shape functions, and a P1
// space (no edge nodes) keeps the chords.
#include <Eigen/Dense>
#include <cmath>

#include "fem/field_space.hpp"

namespace stiction::fem {

// dX/dxi (D x SD) of the simplex with SD + 1 `vertices` and the space's n `nodes` on it
// (vertices, then edges), at a point where the shape functions' reference gradients are dN
// (n x SD, row-major).
template <int D, int SD>
Eigen::Matrix<double, D, SD> simplex_jacobian(const FieldSpace& space, const int* vertices, const int* nodes, int n,
                                              const double* dN) {
  const mesh::Mesh& mesh = space.mesh();
  Eigen::Matrix<double, D, SD> J;
  const double* X0 = mesh.vertex(vertices[0]);
  for (int j = 0; j < SD; ++j)
    for (int i = 0; i < D; ++i) J(i, j) = mesh.vertex(vertices[j + 1])[i] - X0[i];
  if (space.is_curved())
    for (int a = SD + 1; a < n; ++a) {
      const double* g = space.node_offset(nodes[a]);
      for (int j = 0; j < SD; ++j)
        for (int i = 0; i < D; ++i) J(i, j) += g[i] * dN[a * SD + j];
    }
  return J;
}

// X(xi) (D entries) of the same simplex at reference point xi, where the shape functions'
// values are N.
template <int D, int SD>
void simplex_position(const FieldSpace& space, const int* vertices, const int* nodes, int n, const double* xi,
                      const double* N, double* X) {
  const mesh::Mesh& mesh = space.mesh();
  const double* X0 = mesh.vertex(vertices[0]);
  for (int i = 0; i < D; ++i) {
    X[i] = X0[i];
    for (int j = 0; j < SD; ++j) X[i] += (mesh.vertex(vertices[j + 1])[i] - X0[i]) * xi[j];
  }
  if (space.is_curved())
    for (int a = SD + 1; a < n; ++a) {
      const double* g = space.node_offset(nodes[a]);
      for (int i = 0; i < D; ++i) X[i] += g[i] * N[a];
    }
}

// A cell's map at one point: the inverse Jacobian dxi/dX and det(dX/dxi) (positive on a
// valid cell: mesh::check_validity).
template <int D>
struct CellMap {
  Eigen::Matrix<double, D, D> inv;
  double det;
};

template <int D>
CellMap<D> cell_map(const Eigen::Matrix<double, D, D>& J) {
  return {J.inverse(), J.determinant()};
}

// Measure scale of a map dX/dxi (D x SD): sqrt(det(J^T J)), |det J| for a cell.
template <int D, int SD>
double measure_scale(const Eigen::Matrix<double, D, SD>& J) {
  return std::sqrt((J.transpose() * J).determinant());
}

}  // namespace stiction::fem
