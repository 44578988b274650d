#pragma once
// Facets of a contact surface in the current configuration, for 2D (P1/P2 segments, one
// parameter) and 3D (P1/P2 triangles, two parameters), and the closest-point projection of a
// point on one facet (or, 3D, the crossing of a line) with the sensitivity of the projection
// parameter (paper Sec. 4.1: the master point x2 of a slave point x1). Templates on the space dimension D, used by
// surface_contact.cpp; the facet parameter eta has P = D - 1 components (reference simplex).
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "fem/app_view.hpp"
#include "fem/basis.hpp"

namespace stiction::contact {

// One facet of a contact surface: its vertices, its P2 (or P1) nodes, its reference geometry
// X(eta) = X0 + E eta (E's columns the edges from vertex 0), and the sign making
// outward * normal(dx/deta) its outward normal.
struct SurfaceFacet {
  int n_vertices = 0;  // 2 (segment) or 3 (triangle)
  int vertex[3] = {-1, -1, -1};
  std::vector<int> nodes;
  double X0[3] = {0, 0, 0};
  double E[2][3] = {{0, 0, 0}, {0, 0, 0}};
  double outward = 1;
  int node_of_vertex[3] = {-1, -1, -1};  // slave facets: multiplier node of each vertex
  // Curved P2 facet: the reference position is the chord map plus sum_e offset_e N_e(eta)
  // over its edge nodes (fem::FieldSpace::node_offset, in facet-node order after the
  // vertices).
  bool curved = false;
  double offset[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

namespace facets {

template <int D>
struct Geometry {
  static constexpr int P = D - 1;
  using Vec = Eigen::Matrix<double, D, 1>;
  using Param = Eigen::Matrix<double, P, 1>;
  using ParamMatrix = Eigen::Matrix<double, P, P>;
  using Tangents = Eigen::Matrix<double, D, P>;  // column k: dx / deta_k
};

// The unnormalised normal of tangents t: (t_y, -t_x) in 2D, t_0 x t_1 in 3D; its length is
// the surface Jacobian.
template <int D>
typename Geometry<D>::Vec normal_of(const typename Geometry<D>::Tangents& t) {
  if constexpr (D == 2) return {t(1, 0), -t(0, 0)};
  else return t.col(0).cross(t.col(1));
}

template <int D>
typename Geometry<D>::Vec outward_normal(const SurfaceFacet& f, const typename Geometry<D>::Tangents& t) {
  return f.outward * normal_of<D>(t);
}

// d(outward normal) when node a's component c moves by one: the tangents change by
// dN_a e_c (dN_a the P reference derivatives of N_a).
template <int D>
typename Geometry<D>::Vec normal_variation(const SurfaceFacet& f, const typename Geometry<D>::Tangents& t,
                                           const double* dN_a, int c) {
  using Vec = typename Geometry<D>::Vec;
  const Vec e = Vec::Unit(c);
  if constexpr (D == 2) return f.outward * Vec(dN_a[0] * e[1], -dN_a[0] * e[0]);
  else return f.outward * (dN_a[0] * e.cross(t.col(1)) + dN_a[1] * t.col(0).cross(e));
}

template <int D>
typename Geometry<D>::Tangents reference_edges(const SurfaceFacet& f) {
  typename Geometry<D>::Tangents E;
  for (int k = 0; k < D - 1; ++k)
    for (int c = 0; c < D; ++c) E(c, k) = f.E[k][c];
  return E;
}

// The P1 hat of vertex k at eta (barycentric coordinates).
template <int D>
double vertex_hat(int k, const typename Geometry<D>::Param& eta) {
  return k == 0 ? 1 - eta.sum() : eta[k - 1];
}

// A point of a facet at eta in the configuration X + v: position, tangents, second
// derivatives d2x / deta_k deta_l (at k * P + l), and the shape functions there (dN row-major
// n x P).
template <int D>
struct FacetPoint {
  using G = Geometry<D>;
  typename G::Vec x;
  typename G::Tangents dx;
  std::array<typename G::Vec, G::P * G::P> ddx;
  double N[6] = {0, 0, 0, 0, 0, 0}, dN[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  FacetPoint() {
    x.setZero(), dx.setZero();
    for (auto& v : ddx) v.setZero();
  }
  const double* dN_of(int a) const { return dN + a * G::P; }
};

template <int D>
class FacetEvaluator {
public:
  using G = Geometry<D>;
  static constexpr int P = G::P;
  FacetEvaluator(fem::BasisKind kind, int n_nodes) : kind_(kind), n_(n_nodes) {
    // Shape functions are at most quadratic: their second derivatives are the constant
    // differences of the first between eta = 0 and eta = e_l.
    typename G::Param origin = G::Param::Zero();
    double N[6], d0[12], dl[12];
    fem::eval_shape(P, kind_, origin.data(), N, d0);
    for (int l = 0; l < P; ++l) {
      const typename G::Param el = G::Param::Unit(l);
      fem::eval_shape(P, kind_, el.data(), N, dl);
      for (int a = 0; a < n_; ++a)
        for (int k = 0; k < P; ++k) ddN_[a][k * P + l] = dl[a * P + k] - d0[a * P + k];
    }
    if constexpr (D == 3)
      for (int e = 0; e < 3; ++e) {
        const Eigen::Vector2d mid = 0.5 * (corner(e) + corner((e + 1) % 3));
        fem::eval_shape(P, kind_, mid.data(), midpoint_N_[e], d0);
      }
  }
  int n() const { return n_; }

  FacetPoint<D> at(const SurfaceFacet& f, const typename G::Param& eta, fem::StateView v) const {
    FacetPoint<D> p;
    fem::eval_shape(P, kind_, eta.data(), p.N, p.dN);
    const typename G::Tangents E = reference_edges<D>(f);
    p.x = E * eta;
    for (int c = 0; c < D; ++c) p.x[c] += f.X0[c];
    p.dx = E;
    for (int a = 0; a < n_; ++a) {
      const typename G::Vec va = node_displacement(f, a, v);
      p.x += p.N[a] * va;
      for (int k = 0; k < P; ++k) p.dx.col(k) += p.dN[a * P + k] * va;
      for (int kl = 0; kl < P * P; ++kl) p.ddx[kl] += ddN_[a][kl] * va;
    }
    return p;
  }
  // Measure of the reference (undeformed) facet at p per unit reference-simplex measure:
  // |E| in 2D, |E0 x E1| in 3D on a straight facet (the reference triangle has area 1/2),
  // the isoparametric map's on a curved one.
  double reference_measure(const SurfaceFacet& f, const FacetPoint<D>& p) const {
    typename G::Tangents E = reference_edges<D>(f);
    if (f.curved)
      for (int a = f.n_vertices; a < n_; ++a)
        for (int k = 0; k < P; ++k) E.col(k) += p.dN[a * P + k] * offset_of(f, a);
    return std::sqrt((E.transpose() * E).determinant());
  }
  // sum_a N_a v_a at the point's shape values.
  typename G::Vec values(const SurfaceFacet& f, const FacetPoint<D>& p, fem::StateView v) const {
    typename G::Vec out = G::Vec::Zero();
    for (int a = 0; a < n_; ++a) out += p.N[a] * node_value(f, a, v);
    return out;
  }
  // sum_a dN_a/deta_k v_a (column k).
  typename G::Tangents gradients(const SurfaceFacet& f, const FacetPoint<D>& p, fem::StateView v) const {
    typename G::Tangents out = G::Tangents::Zero();
    for (int a = 0; a < n_; ++a) {
      const typename G::Vec va = node_value(f, a, v);
      for (int k = 0; k < P; ++k) out.col(k) += p.dN[a * P + k] * va;
    }
    return out;
  }

  // 3D: the Bezier control net of facet f in the configuration X + v: its vertices, then per
  // edge (i, j) the point 2 x(midpoint) - (x_i + x_j) / 2. A quadratic (or flat) triangle
  // lies in the convex hull of its net: the Bernstein weights are non-negative and sum to one.
  std::array<Eigen::Vector3d, 6> control_net(const SurfaceFacet& f, fem::StateView v) const {
    static_assert(D == 3, "a control net of a triangle");
    std::array<Eigen::Vector3d, 6> net;
    const Eigen::Vector3d X0(f.X0);
    const typename G::Tangents E = reference_edges<D>(f);
    for (int k = 0; k < 3; ++k) net[k] = X0 + E * corner(k) + node_value(f, k, v);
    for (int e = 0; e < 3; ++e) {
      Eigen::Vector3d mid = X0 + E * (0.5 * (corner(e) + corner((e + 1) % 3)));
      for (int a = 0; a < n_; ++a)
        if (midpoint_N_[e][a] != 0) mid += midpoint_N_[e][a] * node_displacement(f, a, v);
      net[3 + e] = 2 * mid - 0.5 * (net[e] + net[(e + 1) % 3]);
    }
    return net;
  }

private:
  static Eigen::Vector2d corner(int k) { return k == 0 ? Eigen::Vector2d(0, 0) : Eigen::Vector2d::Unit(k - 1); }
  static typename G::Vec offset_of(const SurfaceFacet& f, int a) {
    return Eigen::Map<const typename G::Vec>(f.offset[a - f.n_vertices]);
  }
  static typename G::Vec node_value(const SurfaceFacet& f, int a, fem::StateView v) {
    const size_t k = static_cast<size_t>(f.nodes[a]) * D;
    typename G::Vec x;
    for (int c = 0; c < D; ++c) x[c] = v[k + c];
    return x;
  }
  // Node a's coefficient over the chord map X0 + E eta: its value in v, plus a curved
  // facet's reference offset at an edge node.
  static typename G::Vec node_displacement(const SurfaceFacet& f, int a, fem::StateView v) {
    typename G::Vec va = node_value(f, a, v);
    if (f.curved && a >= f.n_vertices) va += offset_of(f, a);
    return va;
  }
  fem::BasisKind kind_;
  int n_;
  double ddN_[6][G::P * G::P] = {};
  double midpoint_N_[3][6] = {};  // 3D: the shape functions at the edge midpoints
};

// A master point y(eta) of x on a facet. For a closest point (project below) `sensitivity`
// maps d F / du to d eta / du, where F_k(eta, u) = (x - y(eta)) . y_,k is the projection
// equation: by the implicit function theorem on the face of the facet where eta lies,
//   d eta = -V (V^T H V)^-1 V^T dF,   H_kl = dF_k / d eta_l = -y_,k . y_,l + (x - y) . y_,kl,
// V a basis of that face's directions in eta: the identity inside the facet, the edge's
// direction on an edge (3D), none at a vertex (eta does not move: sensitivity 0).
//
// For a ray intersection (intersect below, crossing = true) the sensitivity is ray_inverse
// instead: with z = (eta, t) and R(z, u) = x + t nu - y(eta) = 0, dz = -A^-1 dR,
// A = [-y_,eta  nu].
//
// face records where a closest point lies (kInterior: the facet's interior, K = D - 1;
// kEdge0 + e: edge e of a 3D triangle; kVertex: an end vertex): with eta (and t of a
// crossing) it rebuilds the projection without a search (projection_at).
enum ProjectionFace : int { kInterior = 0, kEdge0 = 1, kVertex = 4 };

template <int D>
struct Projection {
  using G = Geometry<D>;
  bool found = false, interior = false, crossing = false;
  int face = kInterior;
  typename G::Param eta = G::Param::Zero();
  typename G::ParamMatrix sensitivity = G::ParamMatrix::Zero();
  double distance = 0, t = 0;
  Eigen::Matrix<double, D, D> ray_inverse = Eigen::Matrix<double, D, D>::Zero();
  FacetPoint<D> y;
};

// Whether the line x + t nu can meet a triangle with control net `net` (control_net): seen
// along nu, the line misses the triangle when x lies beyond one edge line of the vertex
// triangle by more than every control point does. It never rules out a crossing on the
// triangle (edges included): x must lie beyond by 1e-9 of the net's scale, far above
// round-off.
inline bool line_may_cross(const std::array<Eigen::Vector3d, 6>& net, const Eigen::Vector3d& x,
                           const Eigen::Vector3d& nu) {
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d& a = net[e];
    const Eigen::Vector3d edge = net[(e + 1) % 3] - a, across = net[(e + 2) % 3] - a;
    const Eigen::Vector3d w = nu.cross(edge);  // w . (p - a): p's side of the edge line along nu
    const double tolerance = 1e-9 * nu.norm() * edge.norm() * across.norm();
    const double inner = w.dot(across);
    if (std::abs(inner) <= tolerance) continue;  // the line runs along the triangle
    const double sign = inner > 0 ? 1.0 : -1.0;
    double lowest = 0;  // the vertices: 0 on the edge, |inner| opposite
    for (int c = 3; c < 6; ++c) lowest = std::min(lowest, sign * w.dot(net[c] - a));
    if (sign * w.dot(x - a) < lowest - tolerance) return false;
  }
  return true;
}

namespace detail {

// Is eta inside the reference simplex (tolerance tol)?
template <int P>
bool inside(const Eigen::Matrix<double, P, 1>& eta, double tol) {
  return eta.minCoeff() >= -tol && eta.sum() <= 1 + tol;
}

// H of the projection equation at y (see Projection).
template <int D>
typename Geometry<D>::ParamMatrix projection_hessian(const typename Geometry<D>::Vec& x, const FacetPoint<D>& y) {
  constexpr int P = D - 1;
  typename Geometry<D>::ParamMatrix H;
  for (int k = 0; k < P; ++k)
    for (int l = 0; l < P; ++l) H(k, l) = -y.dx.col(k).dot(y.dx.col(l)) + (x - y.x).dot(y.ddx[k * P + l]);
  return H;
}

enum class FaceNewton { Converged, Left, NoMinimum };

// Newton on V^T F(origin + V t) = 0, the closest point of x on one face of a facet: the
// segment or triangle itself (V = I) or a triangle's edge (V its direction), from t.
// Left: the iterate went far off the facet (or did not converge); NoMinimum: -V^T H V is not
// positive definite there (the distance has no minimum along the face).
// Converged when the step falls below 1e-10, then two more (quadratic) steps to round-off.
// A tighter test alone fails for distant points, whose F carries round-off of order
// 1e-16 |x - y| |y'|: measured on self-contact-2d, thousands of projections per evaluation
// stopped short of 1e-15 and, taken for clamped, lost their d eta / du.
template <int D, int K>
FaceNewton face_newton(const FacetEvaluator<D>& ev, const SurfaceFacet& m, const typename Geometry<D>::Vec& x,
                       fem::StateView u, const typename Geometry<D>::Param& origin,
                       const Eigen::Matrix<double, D - 1, K>& V, Eigen::Matrix<double, K, 1>& t) {
  using Param = typename Geometry<D>::Param;
  for (int it = 0, polish = 0; it < 30; ++it) {
    const FacetPoint<D> y = ev.at(m, Param(origin + V * t), u);
    const Eigen::Matrix<double, K, K> HV = V.transpose() * projection_hessian<D>(x, y) * V;
    if (!HV.allFinite() || Eigen::LLT<Eigen::Matrix<double, K, K>>(-HV).info() != Eigen::Success)
      return FaceNewton::NoMinimum;
    const Eigen::Matrix<double, K, 1> F = V.transpose() * (y.dx.transpose() * (x - y.x));
    Eigen::Matrix<double, K, 1> step;
    if constexpr (K == 1) step = F / HV(0, 0);  // (LDLT's pivoting on 1 x 1 trips -Warray-bounds)
    else step = HV.ldlt().solve(F);
    t -= step;
    if (!inside<D - 1>(Param(origin + V * t), 0.5)) return FaceNewton::Left;
    if (step.norm() < 1e-10 && ++polish > 2) return FaceNewton::Converged;
  }
  return FaceNewton::Left;
}

// The projection at eta on the face spanned by V ((D - 1) x K; K = 0 at a vertex, where eta
// does not move).
template <int D, int K>
Projection<D> closest_on_face(const FacetEvaluator<D>& ev, const SurfaceFacet& m, const typename Geometry<D>::Vec& x,
                              fem::StateView u, const typename Geometry<D>::Param& eta,
                              const Eigen::Matrix<double, D - 1, K>& V) {
  Projection<D> p;
  p.found = true;
  p.interior = K == D - 1;
  p.eta = eta;
  p.y = ev.at(m, eta, u);
  p.distance = (x - p.y.x).norm();
  if constexpr (K > 0) {
    const Eigen::Matrix<double, K, K> HV = V.transpose() * projection_hessian<D>(x, p.y) * V;
    p.sensitivity = -V * HV.inverse() * V.transpose();
  }
  return p;
}

// The crossing of the line x + t nu with m at (eta, t), found by intersect.
template <int D>
Projection<D> crossing_at(const FacetEvaluator<D>& ev, const SurfaceFacet& m, const typename Geometry<D>::Vec& x,
                          const typename Geometry<D>::Vec& nu, fem::StateView u,
                          const typename Geometry<D>::Param& eta, double t) {
  Projection<D> p;
  p.found = p.interior = p.crossing = true;
  p.eta = eta;
  p.t = t;
  p.y = ev.at(m, p.eta, u);
  Eigen::Matrix<double, D, D> A;
  A << -p.y.dx, nu;
  p.ray_inverse = A.inverse();
  p.distance = (x - p.y.x).norm();
  return p;
}

}  // namespace detail

// Closest point of x on segment m (2D): Newton from the midpoint; where it converges outside
// [0, 1] or leaves the segment the point is clamped to the nearer end (a vertex). Not found
// when the distance has no minimum along the segment there.
inline Projection<2> project(const FacetEvaluator<2>& ev, const SurfaceFacet& m, const Geometry<2>::Vec& x,
                             fem::StateView u) {
  using Param = Geometry<2>::Param;
  const Eigen::Matrix<double, 1, 1> I = Eigen::Matrix<double, 1, 1>::Identity();
  Param t(0.5);
  const auto result = detail::face_newton<2, 1>(ev, m, x, u, Param::Zero(), I, t);
  if (result == detail::FaceNewton::NoMinimum) return {};
  if (result == detail::FaceNewton::Converged && detail::inside<1>(t, 0))
    return detail::closest_on_face<2, 1>(ev, m, x, u, t, I);
  Projection<2> end =
      detail::closest_on_face<2, 0>(ev, m, x, u, Param(std::clamp(t[0], 0.0, 1.0)), Eigen::Matrix<double, 1, 0>());
  end.face = kVertex;
  return end;
}

// Closest point of x on triangle m (3D, choice of master_point = "closest"): Newton inside
// the triangle from its centroid; where that converges outside or leaves it, the closest
// point on each of the three edges (Newton along the edge, clamped to its end vertices),
// the nearest of them. Not found when the distance has no minimum inside the triangle
// (-H not positive definite) or on any edge.
inline Projection<3> project(const FacetEvaluator<3>& ev, const SurfaceFacet& m, const Geometry<3>::Vec& x,
                             fem::StateView u) {
  using Param = Geometry<3>::Param;
  using Edge = Eigen::Matrix<double, 2, 1>;
  Param t = Param::Constant(1.0 / 3);
  const auto inner = detail::face_newton<3, 2>(ev, m, x, u, Param::Zero(), Eigen::Matrix2d::Identity(), t);
  if (inner == detail::FaceNewton::NoMinimum) return {};
  if (inner == detail::FaceNewton::Converged && detail::inside<2>(t, 0))
    return detail::closest_on_face<3, 2>(ev, m, x, u, t, Eigen::Matrix2d::Identity());
  const Param corner[3] = {Param(0, 0), Param(1, 0), Param(0, 1)};
  Projection<3> best;
  for (int e = 0; e < 3; ++e) {
    const Param a = corner[e];
    const Edge direction = corner[(e + 1) % 3] - a;
    Eigen::Matrix<double, 1, 1> s(0.5);
    const auto along = detail::face_newton<3, 1>(ev, m, x, u, a, direction, s);
    if (along == detail::FaceNewton::NoMinimum) continue;
    const bool on_edge = along == detail::FaceNewton::Converged && s[0] >= 0 && s[0] <= 1;
    Projection<3> p =
        on_edge ? detail::closest_on_face<3, 1>(ev, m, x, u, Param(a + direction * s[0]), direction)
                : detail::closest_on_face<3, 0>(ev, m, x, u, Param(a + direction * std::clamp(s[0], 0.0, 1.0)),
                                                Eigen::Matrix<double, 2, 0>());  // the nearer end vertex
    p.face = on_edge ? kEdge0 + e : kVertex;
    if (!best.found || p.distance < best.distance) best = p;
  }
  return best;
}

// Where the line x + t nu meets facet m (Newton on R(eta, t) = x + t nu - y(eta) = 0 from the
// centroid, t = 0). Found only when the crossing lies on the facet (eta inside it, edges
// included): unlike the closest point, the crossing moves continuously from one facet to the
// next as x moves, because the surface is continuous across its edges. In 3D a line that
// misses the facet's control net is ruled out before Newton (line_may_cross).
template <int D>
Projection<D> intersect(const FacetEvaluator<D>& ev, const SurfaceFacet& m, const typename Geometry<D>::Vec& x,
                        const typename Geometry<D>::Vec& nu, fem::StateView u) {
  using G = Geometry<D>;
  constexpr int P = G::P;
  using Unknowns = Eigen::Matrix<double, D, 1>;  // (eta, t)
  Projection<D> p;
  if constexpr (D == 3)  // most candidates are the crossed facet's neighbours: spare their Newton
    if (!line_may_cross(ev.control_net(m, u), x, nu)) return p;
  Unknowns z = Unknowns::Zero();
  z.template head<P>().setConstant(1.0 / (P + 1));
  Eigen::Matrix<double, D, D> A;
  for (int it = 0; it < 30; ++it) {
    p.y = ev.at(m, z.template head<P>(), u);
    A << -p.y.dx, nu;
    const Unknowns R = x + z[P] * nu - p.y.x;
    // Closed-form inverse (cofactors; a pivoting LU cost more than the rest of the
    // iteration). Singular relative to Hadamard's bound: the line runs along the facet.
    Eigen::Matrix<double, D, D> A_inverse;
    double det = 0;
    bool invertible = false;
    A.computeInverseAndDetWithCheck(A_inverse, det, invertible,
                                    D * std::numeric_limits<double>::epsilon() * A.colwise().norm().prod());
    if (!invertible) return p;
    const Unknowns step = A_inverse * R;
    z -= step;
    if (!detail::inside<P>(typename G::Param(z.template head<P>()), 0.5)) return p;
    // Newton converges quadratically: after a step below 1e-10 the next would be at round-off.
    if (step.template head<P>().norm() < 1e-10) {
      if (!detail::inside<P>(typename G::Param(z.template head<P>()), 0)) return p;
      return detail::crossing_at<D>(ev, m, x, nu, u, z.template head<P>(), z[P]);
    }
  }
  return p;
}

// The projection of kind `face` (or the crossing) at eta (t) on m, as the search found it:
// the same arithmetic as the search's last step, so the same projection to the bit.
template <int D>
Projection<D> projection_at(const FacetEvaluator<D>& ev, const SurfaceFacet& m, const typename Geometry<D>::Vec& x,
                            const typename Geometry<D>::Vec& nu, fem::StateView u, bool crossing,
                            int face, const typename Geometry<D>::Param& eta, double t) {
  using Param = typename Geometry<D>::Param;
  if (crossing) return detail::crossing_at<D>(ev, m, x, nu, u, eta, t);
  if (face == kInterior)
    return detail::closest_on_face<D, D - 1>(ev, m, x, u, eta, Eigen::Matrix<double, D - 1, D - 1>::Identity());
  Projection<D> p;
  if (face == kVertex) {
    p = detail::closest_on_face<D, 0>(ev, m, x, u, eta, Eigen::Matrix<double, D - 1, 0>());
  } else if constexpr (D == 3) {
    const Param corner[3] = {Param(0, 0), Param(1, 0), Param(0, 1)};
    const int e = face - kEdge0;
    const Eigen::Matrix<double, 2, 1> direction = corner[(e + 1) % 3] - corner[e];
    p = detail::closest_on_face<3, 1>(ev, m, x, u, eta, direction);
  }
  p.face = face;
  return p;
}

}  // namespace facets
}  // namespace stiction::contact
