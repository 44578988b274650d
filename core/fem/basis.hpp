#pragma once
// Scalar shape functions on the reference simplex of dimension D (1, 2, 3), in terms of the
// barycentric coordinates l_0 = 1 - sum(x), l_i = x_{i-1}. Local numbering: vertices, then
// edges in mesh::SimplexEdges<D> order.
//
//  P1                vertex hats l_i
//  P2 nodal          l_i (2 l_i - 1) on vertices, 4 l_a l_b on edges (Lagrange)
//  P2 hierarchical   l_i on vertices, 4 l_a l_b on edges (paper Sec. 2.3): the vertex part
//                    is the P1 basis, so the u_l block of the P2 matrix is the P1 matrix.
#include <string>

namespace stiction::fem {

enum class BasisKind { P1, P2Nodal, P2Hierarchical };

std::string to_string(BasisKind k);
BasisKind basis_kind_from_string(const std::string& s);  // "p1", "p2-nodal", "p2" / "p2-hierarchical"

constexpr bool is_quadratic(BasisKind k) { return k != BasisKind::P1; }
constexpr int n_shape_functions(int d, BasisKind k) {
  return is_quadratic(k) ? (d + 1) * (d + 2) / 2 : d + 1;
}

// Values (n) and reference gradients (n x d, row-major) at reference point xi.
void eval_shape(int d, BasisKind k, const double* xi, double* values, double* ref_grads);

}  // namespace stiction::fem
