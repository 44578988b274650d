#include "fem/basis.hpp"

#include <fmt/format.h>

#include "common/error.hpp"
#include "mesh/mesh.hpp"

namespace stiction::fem {

std::string to_string(BasisKind k) {
  switch (k) {
    case BasisKind::P1: return "p1";
    case BasisKind::P2Nodal: return "p2-nodal";
    case BasisKind::P2Hierarchical: return "p2-hierarchical";
  }
  return "?";
}

BasisKind basis_kind_from_string(const std::string& s) {
  if (s == "p1") return BasisKind::P1;
  if (s == "p2-nodal") return BasisKind::P2Nodal;
  if (s == "p2" || s == "p2-hierarchical") return BasisKind::P2Hierarchical;
  throw Error(fmt::format("unknown basis '{}' (accepted: p1, p2-hierarchical, p2-nodal)", s));
}

void eval_shape(int d, BasisKind k, const double* xi, double* N, double* dN) {
  double l[4], dl[4][3] = {};
  l[0] = 1;
  for (int i = 0; i < d; ++i) {
    l[0] -= xi[i];
    l[i + 1] = xi[i];
    dl[0][i] = -1;
    dl[i + 1][i] = 1;
  }
  for (int v = 0; v <= d; ++v) {
    const bool nodal = k == BasisKind::P2Nodal;
    N[v] = nodal ? l[v] * (2 * l[v] - 1) : l[v];
    for (int j = 0; j < d; ++j) dN[v * d + j] = nodal ? (4 * l[v] - 1) * dl[v][j] : dl[v][j];
  }
  if (!is_quadratic(k)) return;
  for (int e = 0; e < mesh::n_simplex_edges(d); ++e) {
    const auto [a, b] = mesh::simplex_edge(d, e);
    const int i = d + 1 + e;
    N[i] = 4 * l[a] * l[b];
    for (int j = 0; j < d; ++j) dN[i * d + j] = 4 * (dl[a][j] * l[b] + l[a] * dl[b][j]);
  }
}

}  // namespace stiction::fem
