#include "fem/elasticity_assembly.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "common/error.hpp"
#include "common/petsc.hpp"
#include "fem/cell_geometry.hpp"
#include "fem/quadrature.hpp"

namespace stiction::fem {

namespace {

using materials::Mat3;

// Shape-function values and reference gradients tabulated at a rule's points.
struct Tabulation {
  QuadratureRule rule;
  int n = 0;                  // shape functions
  std::vector<double> N;      // q x n
  std::vector<double> dN;     // q x n x d
};

Tabulation tabulate(int d, BasisKind kind, int degree) {
  Tabulation t{simplex_quadrature(d, degree), n_shape_functions(d, kind), {}, {}};
  t.N.resize(static_cast<size_t>(t.rule.size()) * t.n);
  t.dN.resize(static_cast<size_t>(t.rule.size()) * t.n * d);
  for (int q = 0; q < t.rule.size(); ++q)
    eval_shape(d, kind, t.rule.point(q), &t.N[static_cast<size_t>(q) * t.n], &t.dN[static_cast<size_t>(q) * t.n * d]);
  return t;
}

// Reference gradients of the shape functions at the nodes of a quadratic cell (its vertices,
// then its edge midpoints in the local edge order): where det F is checked besides the
// quadrature points (internal_kernel).
std::vector<double> gradients_at_nodes(int d, BasisKind kind) {
  const int n = n_shape_functions(d, kind);
  std::vector<std::array<double, 3>> points(d + 1, {0, 0, 0});
  for (int k = 0; k < d; ++k) points[k + 1][k] = 1;
  for (int e = 0; e < mesh::n_simplex_edges(d); ++e) {
    const auto [a, b] = mesh::simplex_edge(d, e);
    std::array<double, 3> mid{0, 0, 0};
    for (int k = 0; k < d; ++k) mid[k] = 0.5 * (points[a][k] + points[b][k]);
    points.push_back(mid);
  }
  std::vector<double> dN(points.size() * n * d), values(n);
  for (size_t q = 0; q < points.size(); ++q) eval_shape(d, kind, points[q].data(), values.data(), &dN[q * n * d]);
  return dN;
}

// Physical gradients G (n x D) of the shape functions at one quadrature point.
template <int D, int NB>
void physical_gradients(const double* dNref, const Eigen::Matrix<double, D, D>& inv, double (&G)[NB][D]) {
  for (int a = 0; a < NB; ++a)
    for (int J = 0; J < D; ++J) {
      double s = 0;
      for (int j = 0; j < D; ++j) s += dNref[a * D + j] * inv(j, J);
      G[a][J] = s;
    }
}

// F = I + sum_a u_a (x) G_a, embedded in 3x3 (plane strain: F_33 = 1).
template <int D, int NB>
Mat3 deformation_gradient(const double (&ue)[NB][D], const double (&G)[NB][D]) {
  Mat3 F = Mat3::Identity();
  for (int a = 0; a < NB; ++a)
    for (int i = 0; i < D; ++i)
      for (int J = 0; J < D; ++J) F(i, J) += ue[a][i] * G[a][J];
  return F;
}

// Pressure terms of a mixed cell at one quadrature point (paper (2)-(6)). Sign convention:
// the pressure equation is written as  -int ((J - 1) + p / kappa) q = 0,  so that the
// Newton matrix is symmetric, [A Bp^T; Bp -(1/kappa) Mp] with Bp = -int J F^-T : grad(du) q;
// its pressure Schur complement -(1/kappa) Mp - Bp A^-1 Bp^T is negative, like the MHP
// approximation alpha Mp with alpha = -(1/mu10 + 1/kappa) < 0.
//   P <- P' - p J F^-T,   A <- A' - p (J G_iJ G_kL - J G_iL G_kJ),   G = F^-T.
void add_pressure_to_stress(const Mat3& G, double J, double p, Mat3& P, materials::Tangent* A) {
  P -= p * J * G;
  if (!A) return;
  for (int i = 0; i < 3; ++i)
    for (int Jx = 0; Jx < 3; ++Jx)
      for (int k = 0; k < 3; ++k)
        for (int L = 0; L < 3; ++L)
          (*A)[materials::tangent_index(i, Jx, k, L)] -= p * J * (G(i, Jx) * G(k, L) - G(i, L) * G(k, Jx));
}

// Cell c's map at a point where the space's reference gradients are dN (the chord map on a
// straight cell, where dN does not matter).
template <int D, int NB>
CellMap<D> map_of_cell(const FieldSpace& space, int c, const int* nodes, const double* dN) {
  return cell_map<D>(simplex_jacobian<D, D>(space, space.mesh().cell(c), nodes, NB, dN));
}

template <int D, int NB>
InternalForceStatus internal_kernel(const FieldSpace& space, const std::vector<const materials::Material*>& mat,
                                    StateView u, ResidualView residual, StiffnessMatrix* tangent,
                                    const std::vector<int>* cells) {
  constexpr int ND = NB * D, NP = D + 1, MD = ND + NP;  // element dofs: u, then (mixed) p
  const Tabulation tab = tabulate(D, space.kind(), 2);  // nodal and hierarchical P2 share NB
  const std::vector<double> node_gradients = NB > D + 1 ? gradients_at_nodes(D, space.kind()) : std::vector<double>{};
  const mesh::Mesh& mesh = space.mesh();
  InternalForceStatus status;
  int nodes[NB];
  int idx[MD];
  double ue[NB][D], pe[NP], G[NB][D], lp[NP];
  std::vector<double> Ke(MD * MD);
  double re[MD];
  double C[NB][D][D][D];  // C[b][i][J][k] = w sum_L A_iJkL G_bL
  materials::Tangent A;
  Mat3 P;

  const int n_cells = cells ? static_cast<int>(cells->size()) : mesh.n_cells();
  for (int k = 0; k < n_cells; ++k) {
    const int c = cells ? (*cells)[k] : k;
    const double kappa = mat[c]->mixed_bulk_modulus();
    const int np = kappa > 0 ? NP : 0, m = ND + np;
    space.cell_nodes(c, nodes);
    for (int a = 0; a < NB; ++a)
      for (int i = 0; i < D; ++i) {
        idx[a * D + i] = nodes[a] * D + i;
        ue[a][i] = u[static_cast<size_t>(nodes[a]) * D + i];
      }
    for (int a = 0; a < np; ++a) {
      idx[ND + a] = space.pressure_dof(nodes[a]);
      pe[a] = u[idx[ND + a]];
    }
    const bool curved = space.is_curved_cell(c);
    CellMap<D> geo = map_of_cell<D, NB>(space, c, nodes, tab.dN.data());
    // A quadratic cell can fold at its boundary (an edge curving back on itself) while det F
    // stays positive at every quadrature point, and the degree-2 rule's energy does not see
    // the fold: measured on the frictional ironing at level 1, Newton converged at t = 1.49
    // to a state with det F = -8.5e-3 at a slab-top vertex (0.48 at the cell's quadrature
    // points) and then stalled, the contact projections on the looped master facet jumping.
    // det F at the nodes too (necessary for a valid cell, not sufficient: a bound over the
    // whole cell needs Bernstein coefficients of det F, Johnen, Remacle & Geuzaine 2013).
    const bool finite_strain = mat[c]->requires_positive_jacobian();
    if (NB > D + 1 && finite_strain)
      for (int k = 0; k < NB; ++k) {
        const double* dN_k = &node_gradients[static_cast<size_t>(k) * NB * D];
        if (curved) geo = map_of_cell<D, NB>(space, c, nodes, dN_k);
        physical_gradients<D, NB>(dN_k, geo.inv, G);
        const double det_node = deformation_gradient<D, NB>(ue, G).determinant();
        if (det_node < status.min_det_f) status.min_det_f = det_node, status.min_det_f_cell = c;
        if (!(det_node > 0) && status.folded_cell < 0) status.folded_cell = c;
      }
    if (tangent) std::fill(Ke.begin(), Ke.begin() + m * m, 0.0);
    std::fill(re, re + m, 0.0);
    for (int q = 0; q < tab.rule.size(); ++q) {
      const double* dN_q = &tab.dN[static_cast<size_t>(q) * NB * D];
      if (curved) geo = map_of_cell<D, NB>(space, c, nodes, dN_q);
      physical_gradients<D, NB>(dN_q, geo.inv, G);
      const Mat3 F = deformation_gradient<D, NB>(ue, G);
      const double detF = F.determinant();
      if (finite_strain && detF < status.min_det_f) status.min_det_f = detF, status.min_det_f_cell = c;
      if (!(detF > 0) && finite_strain) {
        if (status.inverted_cell < 0) status.inverted_cell = c;
        continue;
      }
      const double w = tab.rule.weights[q] * std::abs(geo.det);
      // P1 pressure shape functions: the barycentric coordinates.
      double p = 0;
      if (np) {
        const double* xi = tab.rule.point(q);
        lp[0] = 1;
        for (int j = 0; j < D; ++j) lp[0] -= xi[j], lp[j + 1] = xi[j];
        for (int a = 0; a < NP; ++a) p += lp[a] * pe[a];
      }
      const Mat3 Finv_T = np ? Mat3(F.inverse().transpose()) : Mat3::Zero();
      if (!tangent) {
        P = mat[c]->first_piola(F);
        if (np) add_pressure_to_stress(Finv_T, detF, p, P, nullptr);
      } else {
        mat[c]->first_piola_and_tangent(F, P, A);
        if (np) add_pressure_to_stress(Finv_T, detF, p, P, &A);
        for (int b = 0; b < NB; ++b)
          for (int i = 0; i < D; ++i)
            for (int J = 0; J < D; ++J)
              for (int k = 0; k < D; ++k) {
                double s = 0;
                for (int L = 0; L < D; ++L) s += A[materials::tangent_index(i, J, k, L)] * G[b][L];
                C[b][i][J][k] = w * s;
              }
        // Major symmetry of A (hyperelastic): fill the upper block triangle, mirror below.
        for (int a = 0; a < NB; ++a)
          for (int b = a; b < NB; ++b)
            for (int i = 0; i < D; ++i)
              for (int k = 0; k < D; ++k) {
                double s = 0;
                for (int J = 0; J < D; ++J) s += G[a][J] * C[b][i][J][k];
                Ke[(a * D + i) * m + b * D + k] += s;
              }
        if (np) {
          for (int a = 0; a < NB; ++a)  // Bp^T: -w J (F^-T grad N_a)_i q_b, and its transpose
            for (int i = 0; i < D; ++i) {
              double g = 0;
              for (int J = 0; J < D; ++J) g += Finv_T(i, J) * G[a][J];
              for (int b = 0; b < NP; ++b) {
                const double v = -w * detF * g * lp[b];
                Ke[(a * D + i) * m + ND + b] += v;
                Ke[(ND + b) * m + a * D + i] += v;
              }
            }
          for (int a = 0; a < NP; ++a)  // -(1/kappa) Mp
            for (int b = 0; b < NP; ++b) Ke[(ND + a) * m + ND + b] -= w / kappa * lp[a] * lp[b];
        }
      }
      for (int a = 0; a < NB; ++a)
        for (int i = 0; i < D; ++i) {
          double s = 0;
          for (int J = 0; J < D; ++J) s += P(i, J) * G[a][J];
          re[a * D + i] += w * s;
        }
      for (int a = 0; a < np; ++a) re[ND + a] -= w * ((detF - 1) + p / kappa) * lp[a];
    }
    if (residual)
      for (int k = 0; k < m; ++k) residual[idx[k]] += re[k];
    if (tangent) {
      for (int a = 0; a < NB; ++a)
        for (int b = 0; b < a; ++b)
          for (int i = 0; i < D; ++i)
            for (int k = 0; k < D; ++k) Ke[(a * D + i) * m + b * D + k] = Ke[(b * D + k) * m + a * D + i];
      tangent->add(nodes, NB, np, Ke.data());
    }
  }
  return status;
}

template <class F>
auto dispatch(const FieldSpace& space, F&& f) {
  const bool quad = is_quadratic(space.kind());
  switch (space.dim() * 10 + (quad ? 2 : 1)) {
    case 21: return f(std::integral_constant<int, 2>{}, std::integral_constant<int, 3>{});
    case 22: return f(std::integral_constant<int, 2>{}, std::integral_constant<int, 6>{});
    case 31: return f(std::integral_constant<int, 3>{}, std::integral_constant<int, 4>{});
    case 32: return f(std::integral_constant<int, 3>{}, std::integral_constant<int, 10>{});
  }
  throw Error(fmt::format("assembly: unsupported dimension {}", space.dim()), ErrorKind::Internal);
}

// Integrates residual -= int g(X) N_a over simplices of dimension SD (cells or boundary
// facets, curved where the space is) given by their nodes and vertices, skipping those with
// a node that residual's storage does not hold (on several processes, a simplex that
// reaches a process's owned rows has every node held: ghosted_vector.hpp).
template <int D, int SD>
void subtract_load_on(const FieldSpace& space, const std::vector<std::vector<int>>& simplex_nodes,
                      const std::vector<const int*>& simplex_vertices, const VectorField& g, ResidualView residual) {
  const Tabulation tab = tabulate(SD, space.kind(), 4);
  double X[3], val[3];
  for (size_t s = 0; s < simplex_nodes.size(); ++s) {
    const int* v = simplex_vertices[s];
    const int* nodes = simplex_nodes[s].data();
    if (!std::all_of(nodes, nodes + tab.n, [&](int n) { return residual.holds(static_cast<size_t>(n) * D); }))
      continue;
    for (int q = 0; q < tab.rule.size(); ++q) {
      const double* N = &tab.N[static_cast<size_t>(q) * tab.n];
      const auto J = simplex_jacobian<D, SD>(space, v, nodes, tab.n, &tab.dN[static_cast<size_t>(q) * tab.n * SD]);
      simplex_position<D, SD>(space, v, nodes, tab.n, tab.rule.point(q), N, X);
      g(X, val);
      const double w = tab.rule.weights[q] * measure_scale<D, SD>(J);
      for (int a = 0; a < tab.n; ++a)
        for (int i = 0; i < D; ++i) residual[static_cast<size_t>(nodes[a]) * D + i] -= w * N[a] * val[i];
    }
  }
}

void subtract_load(const FieldSpace& space, int sd, const std::vector<std::vector<int>>& simplex_nodes,
                   const std::vector<const int*>& simplex_vertices, const VectorField& g,
                   ResidualView residual) {
  switch (space.dim() * 10 + sd) {
    case 21: return subtract_load_on<2, 1>(space, simplex_nodes, simplex_vertices, g, residual);
    case 22: return subtract_load_on<2, 2>(space, simplex_nodes, simplex_vertices, g, residual);
    case 32: return subtract_load_on<3, 2>(space, simplex_nodes, simplex_vertices, g, residual);
    case 33: return subtract_load_on<3, 3>(space, simplex_nodes, simplex_vertices, g, residual);
  }
  throw Error(fmt::format("assembly: unsupported load on {}-simplices in {}D", sd, space.dim()), ErrorKind::Internal);
}

}  // namespace

InternalForceStatus assemble_internal(const FieldSpace& space,
                                      const std::vector<const materials::Material*>& cell_material,
                                      StateView u, ResidualView residual, StiffnessMatrix* tangent,
                                      const std::vector<int>* cells) {
  return dispatch(space, [&](auto D, auto NB) {
    return internal_kernel<decltype(D)::value, decltype(NB)::value>(space, cell_material, u, residual, tangent, cells);
  });
}

void subtract_body_force(const FieldSpace& space, const VectorField& f, ResidualView residual) {
  const int nc = space.mesh().n_cells();
  std::vector<std::vector<int>> nodes(nc, std::vector<int>(space.nodes_per_cell()));
  std::vector<const int*> verts(nc);
  for (int c = 0; c < nc; ++c) {
    space.cell_nodes(c, nodes[c].data());
    verts[c] = space.mesh().cell(c);
  }
  subtract_load(space, space.dim(), nodes, verts, f, residual);
}

void subtract_traction(const FieldSpace& space, int facet_tag, const VectorField& t,
                       ResidualView residual) {
  std::vector<std::vector<int>> nodes;
  std::vector<const int*> verts;
  for (int f = 0; f < space.mesh().n_facets(); ++f) {
    if (space.mesh().facet_tags[f] != facet_tag) continue;
    nodes.emplace_back(space.nodes_per_facet());
    space.facet_nodes(f, nodes.back().data());
    verts.push_back(space.mesh().facet(f));
  }
  subtract_load(space, space.dim() - 1, nodes, verts, t, residual);
}

Mat assemble_pressure_mass(const DofLayout& layout, const FieldSpace& space) {
  const int d = space.dim(), n = space.n_pressure_dofs(), first = space.pressure_block().first;
  const std::vector<PetscInt> row = layout.block_numbering(first, first + n);
  const PetscInt n_owned = static_cast<PetscInt>(layout.owned_indices(first, first + n).size());
  Mat M;
  // The block's size is the sum of the owned counts (a part's space holds fewer pressures).
  STICTION_PETSC(MatCreateAIJ(layout.comm(), n_owned, n_owned, PETSC_DETERMINE, PETSC_DETERMINE, 32, nullptr, 32, nullptr, &M));
  for (int c : layout.owned_cells()) {  // every cell on one rank
    const int* v = space.mesh().cell(c);
    if (space.pressure_dof(v[0]) < 0) continue;
    // The chord cell's volume: the matrix is a preconditioner's Schur approximation.
    const double vol = std::abs(mesh::signed_measure(space.mesh(), c));
    PetscInt idx[4];
    double Me[16];
    // Exact P1 element mass matrix: |K| (1 + delta_ab) / ((d + 1)(d + 2)).
    for (int a = 0; a <= d; ++a) {
      idx[a] = row[static_cast<size_t>(space.pressure_dof(v[a]) - first)];
      for (int b = 0; b <= d; ++b) Me[a * (d + 1) + b] = vol * (a == b ? 2.0 : 1.0) / ((d + 1) * (d + 2));
    }
    STICTION_PETSC(MatSetValues(M, d + 1, idx, d + 1, idx, Me, ADD_VALUES));
  }
  STICTION_PETSC(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  return M;
}

std::vector<double> cell_cauchy_stress(const FieldSpace& space,
                                       const std::vector<const materials::Material*>& cell_material,
                                       StateView u, const std::vector<int>* cells) {
  return dispatch(space, [&](auto Dc, auto NBc) {
    constexpr int D = decltype(Dc)::value, NB = decltype(NBc)::value;
    const int n = cells ? static_cast<int>(cells->size()) : space.mesh().n_cells();
    std::vector<double> out;
    out.reserve(static_cast<size_t>(n) * 9);
    double centroid[D], N[NB], dN[NB * D], ue[NB][D], G[NB][D];
    std::fill(centroid, centroid + D, 1.0 / (D + 1));
    eval_shape(D, space.kind(), centroid, N, dN);
    int nodes[NB];
    for (int k = 0; k < n; ++k) {
      const int c = cells ? (*cells)[k] : k;
      space.cell_nodes(c, nodes);
      for (int a = 0; a < NB; ++a)
        for (int i = 0; i < D; ++i) ue[a][i] = u[static_cast<size_t>(nodes[a]) * D + i];
      physical_gradients<D, NB>(dN, map_of_cell<D, NB>(space, c, nodes, dN).inv, G);
      Mat3 sigma = cell_material[c]->cauchy(deformation_gradient<D, NB>(ue, G));
      if (cell_material[c]->mixed_bulk_modulus() > 0) {  // sigma = sigma' - p I, p at the centroid
        double p = 0;
        for (int a = 0; a <= D; ++a) p += u[space.pressure_dof(nodes[a])] / (D + 1);
        sigma -= p * Mat3::Identity();
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out.push_back(sigma(i, j));
    }
    return out;
  });
}

std::array<double, 3> boundary_force(const FieldSpace& space, const std::vector<const materials::Material*>& cell_material,
                                     StateView u, int facet_tag, const DofLayout* layout) {
  const mesh::Mesh& mesh = space.mesh();
  // The cell of each tagged facet and the cell's local vertex opposite to it.
  std::map<std::vector<int>, std::pair<int, int>> owner;
  for (int f = 0; f < mesh.n_facets(); ++f)
    if (mesh.facet_tags[f] == facet_tag) {
      std::vector<int> key(mesh.facet(f), mesh.facet(f) + mesh.dim);
      std::sort(key.begin(), key.end());
      if (layout && !layout->owns(static_cast<PetscInt>(key[0]) * mesh.dim)) continue;
      owner[key] = {-1, -1};
    }
  for (int c = 0; c < mesh.n_cells(); ++c)
    for (int k = 0; k <= mesh.dim; ++k) {
      std::vector<int> key;
      for (int j = 0; j <= mesh.dim; ++j)
        if (j != k) key.push_back(mesh.cell(c)[j]);
      std::sort(key.begin(), key.end());
      auto it = owner.find(key);
      if (it != owner.end()) it->second = {c, k};
    }
  return dispatch(space, [&](auto Dc, auto NBc) {
    constexpr int D = decltype(Dc)::value, NB = decltype(NBc)::value;
    const QuadratureRule rule = simplex_quadrature(D - 1, 4);
    std::array<double, 3> force{0, 0, 0};
    int nodes[NB];
    double N[NB], dN[NB * D], ue[NB][D], G[NB][D];
    for (const auto& [key, where] : owner) {
      const auto [c, opposite] = where;
      if (c < 0) throw Error("boundary force: a tagged facet belongs to no cell", ErrorKind::Internal);
      const int* v = mesh.cell(c);
      int local[D];  // cell-local vertices of the facet
      for (int j = 0, k = 0; j <= D; ++j)
        if (j != opposite) local[k++] = j;
      // Outward normal times the facet's measure in the reference cell, per unit measure of
      // the (D-1)-simplex the rule integrates over: the slanted facet opposite vertex 0 is
      // sqrt(D) times larger with normal (1, ..., 1) / sqrt(D), the others have -e_(k-1).
      // Nanson's formula carries it to the (possibly curved) cell: |det J| J^-T a_ref.
      Eigen::Matrix<double, D, 1> a_ref = Eigen::Matrix<double, D, 1>::Zero();
      if (opposite == 0) a_ref.setOnes();
      else a_ref[opposite - 1] = -1;
      space.cell_nodes(c, nodes);
      for (int a = 0; a < NB; ++a)
        for (int i = 0; i < D; ++i) ue[a][i] = u[static_cast<size_t>(nodes[a]) * D + i];
      for (int q = 0; q < rule.size(); ++q) {
        // The facet point in the cell's reference coordinates: barycentric weights of the
        // facet's vertices placed on the cell's reference vertices (vertex 0 at the origin).
        double bary[D + 1] = {}, xi[D] = {};
        bary[local[0]] = 1;
        for (int j = 0; j < D - 1; ++j) bary[local[0]] -= rule.point(q)[j], bary[local[j + 1]] = rule.point(q)[j];
        for (int j = 1; j <= D; ++j) xi[j - 1] = bary[j];
        eval_shape(D, space.kind(), xi, N, dN);
        const CellMap<D> geo = map_of_cell<D, NB>(space, c, nodes, dN);
        const Eigen::Matrix<double, D, 1> area_normal = std::abs(geo.det) * geo.inv.transpose() * a_ref;
        physical_gradients<D, NB>(dN, geo.inv, G);
        const Mat3 F = deformation_gradient<D, NB>(ue, G);
        Mat3 P = cell_material[c]->first_piola(F);
        if (cell_material[c]->mixed_bulk_modulus() > 0) {
          double p = 0;
          for (int j = 0; j <= D; ++j) p += bary[j] * u[space.pressure_dof(v[j])];
          add_pressure_to_stress(F.inverse().transpose(), F.determinant(), p, P, nullptr);
        }
        for (int i = 0; i < D; ++i)
          for (int J = 0; J < D; ++J) force[i] += rule.weights[q] * P(i, J) * area_normal[J];
      }
    }
    return force;
  });
}

}  // namespace stiction::fem
