#include "contact/surface_contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <map>
#include <set>

#include "common/error.hpp"
#include "fem/quadrature.hpp"

namespace stiction::contact {

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BoxPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using Box = bg::model::box<BoxPoint>;
using Vec2 = Eigen::Vector2d;
using Facet = SurfaceContact::Facet;

Vec3 lift(const Vec2& v) { return {v[0], v[1], 0.0}; }

// column[key] += v, starting from zero (Eigen's fixed-size vectors are not zero-initialised).
template <class V>
void accumulate(std::map<PetscInt, V>& columns, PetscInt key, const V& v) {
  columns.try_emplace(key, V::Zero()).first->second += v;
}

// A point of a facet at parameter xi in the configuration X + v: position, tangent
// dx/dxi, second derivative, and the shape functions there.
struct FacetPoint {
  Vec2 x, dx, ddx;
  double N[3] = {0, 0, 0}, dN[3] = {0, 0, 0};
};

class FacetEvaluator {
public:
  FacetEvaluator(fem::BasisKind kind, int n_nodes) : kind_(kind), n_(n_nodes) {
    double N[3], d0[3], d1[3];
    double xi = 0;
    fem::eval_shape(1, kind_, &xi, N, d0);
    xi = 1;
    fem::eval_shape(1, kind_, &xi, N, d1);
    for (int a = 0; a < n_; ++a) ddN_[a] = d1[a] - d0[a];  // shape functions are at most quadratic
  }
  int n() const { return n_; }
  FacetPoint at(const Facet& f, double xi, const std::vector<double>& v) const {
    FacetPoint p;
    fem::eval_shape(1, kind_, &xi, p.N, p.dN);
    p.x = Vec2(f.X0[0] + xi * f.E[0], f.X0[1] + xi * f.E[1]);
    p.dx = Vec2(f.E[0], f.E[1]);
    p.ddx = Vec2::Zero();
    for (int a = 0; a < n_; ++a) {
      const Vec2 va = node_value(f, a, v);
      p.x += p.N[a] * va;
      p.dx += p.dN[a] * va;
      p.ddx += ddN_[a] * va;
    }
    return p;
  }
  // sum_a g_a(xi) v_a for the given shape values g (N or dN).
  Vec2 combine(const Facet& f, const double* g, const std::vector<double>& v) const {
    Vec2 out = Vec2::Zero();
    for (int a = 0; a < n_; ++a) out += g[a] * node_value(f, a, v);
    return out;
  }

private:
  static Vec2 node_value(const Facet& f, int a, const std::vector<double>& v) {
    const size_t k = static_cast<size_t>(f.nodes[a]) * 2;
    return {v[k], v[k + 1]};
  }
  fem::BasisKind kind_;
  int n_;
  double ddN_[3] = {0, 0, 0};
};

Vec2 outward_normal(const Facet& f, const Vec2& tangent) { return f.outward * Vec2(tangent[1], -tangent[0]); }

// Closest point of x on master facet m, with eta clamped to the facet: Newton on
// F(eta) = (x - y(eta)) . y'(eta). `interior` is false when the clamp acted (the point
// projects on an end vertex, where eta does not move with u).
struct Projection {
  bool found = false, interior = false;
  double eta = 0, F_eta = 0, distance = 0;
  FacetPoint y;
};

Projection project(const FacetEvaluator& ev, const Facet& m, const Vec2& x, const std::vector<double>& u) {
  Projection p;
  double eta = 0.5;
  bool converged = false;
  // Converged when the step falls below 1e-10, then two more (quadratic) steps to round-off.
  // A tighter test alone fails for distant points, whose F carries round-off of order
  // 1e-16 |x - y| |y'|: measured on self-contact-2d, thousands of projections per
  // evaluation stopped short of 1e-15 and, taken for clamped, lost their d eta / du.
  for (int it = 0, polish = 0; it < 30; ++it) {
    p.y = ev.at(m, eta, u);
    const Vec2 r = x - p.y.x;
    const double F = r.dot(p.y.dx), F_eta = -p.y.dx.squaredNorm() + r.dot(p.y.ddx);
    if (!(F_eta < 0)) return p;  // not a minimum of the distance along the facet
    const double step = F / F_eta;
    eta -= step;
    if (eta < -0.5 || eta > 1.5) break;  // far off this facet: clamp below
    if (std::abs(step) < 1e-10 && ++polish > 2) {
      converged = true;
      break;
    }
  }
  if (converged && eta >= 0 && eta <= 1) {
    p.y = ev.at(m, eta, u);
    p.interior = true;
    p.F_eta = -p.y.dx.squaredNorm() + (x - p.y.x).dot(p.y.ddx);
  } else {
    eta = std::clamp(eta, 0.0, 1.0);
    p.y = ev.at(m, eta, u);
    p.interior = false;
  }
  p.found = true;
  p.eta = eta;
  p.distance = (x - p.y.x).norm();
  return p;
}

// Slave parameter xi whose projection on facet m lands on m's end `end` (0 or 1):
// (x1(xi) - y_e) . y'_e = 0. Returns NaN when the slave facet is parallel to that normal.
double segment_break(const FacetEvaluator& ev, const Facet& slave, const Facet& m, int end, const std::vector<double>& u) {
  const FacetPoint ye = ev.at(m, end, u);
  double xi = 0.5;
  for (int it = 0; it < 30; ++it) {
    const FacetPoint s = ev.at(slave, xi, u);
    const double h = (s.x - ye.x).dot(ye.dx), dh = s.dx.dot(ye.dx);
    if (!(std::abs(dh) > 1e-14 * s.dx.norm() * ye.dx.norm())) return std::nan("");
    const double step = h / dh;
    xi -= step;
    if (std::abs(step) < 1e-15) return xi;
  }
  return xi;
}

Box facet_box(const FacetEvaluator& ev, const Facet& f, const std::vector<double>& u, double margin) {
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (double xi : {0.0, 0.5, 1.0}) {
    const Vec2 x = ev.at(f, xi, u).x;
    for (int c = 0; c < 2; ++c) lo[c] = std::min(lo[c], x[c]), hi[c] = std::max(hi[c], x[c]);
  }
  return Box(BoxPoint(lo[0] - margin, lo[1] - margin), BoxPoint(hi[0] + margin, hi[1] + margin));
}

std::vector<Facet> collect_facets(const fem::FieldSpace& space, int tag) {
  const mesh::Mesh& mesh = space.mesh();
  std::vector<Facet> out;
  std::map<std::pair<int, int>, int> opposite;  // sorted facet vertices -> interior vertex
  for (int f = 0; f < mesh.n_facets(); ++f) {
    if (mesh.facet_tags[f] != tag) continue;
    Facet F;
    F.vertex[0] = mesh.facet(f)[0], F.vertex[1] = mesh.facet(f)[1];
    F.nodes.resize(space.nodes_per_facet());
    space.facet_nodes(f, F.nodes.data());
    for (int c = 0; c < 2; ++c) {
      F.X0[c] = mesh.vertex(F.vertex[0])[c];
      F.E[c] = mesh.vertex(F.vertex[1])[c] - F.X0[c];
    }
    opposite[{std::min(F.vertex[0], F.vertex[1]), std::max(F.vertex[0], F.vertex[1])}] = -1;
    out.push_back(F);
  }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const int* v = mesh.cell(c);
    for (int k = 0; k < 3; ++k) {
      auto it = opposite.find({std::min(v[k], v[(k + 1) % 3]), std::max(v[k], v[(k + 1) % 3])});
      if (it != opposite.end()) it->second = v[(k + 2) % 3];
    }
  }
  for (Facet& F : out) {
    const int interior = opposite.at({std::min(F.vertex[0], F.vertex[1]), std::max(F.vertex[0], F.vertex[1])});
    if (interior < 0) throw Error("contact: a contact facet belongs to no cell", ErrorKind::Internal);
    const Vec2 inward(mesh.vertex(interior)[0] - F.X0[0], mesh.vertex(interior)[1] - F.X0[1]);
    F.outward = outward_normal(F, Vec2(F.E[0], F.E[1])).dot(inward) < 0 ? 1.0 : -1.0;
  }
  return out;
}

bool share_vertex(const Facet& a, const Facet& b) {
  for (int i : a.vertex)
    for (int j : b.vertex)
      if (i == j) return true;
  return false;
}

// The end (0 or 1) of facet a that is a vertex of facet b, or -1.
int shared_end(const Facet& a, const Facet& b) {
  for (int e = 0; e < 2; ++e)
    if (a.vertex[e] == b.vertex[0] || a.vertex[e] == b.vertex[1]) return e;
  return -1;
}

// One master facet's share of a contact point: its projection, its weight, and (with
// derivatives) d eta / du by the implicit function theorem on F(eta, u) = (x1 - y(eta)) . y'(eta).
struct Branch {
  const Facet* facet = nullptr;
  Projection p;
  double weight = 1;
  std::vector<std::pair<PetscInt, double>> deta;
};

void projection_derivative(const FacetEvaluator& ev, const Facet& slave, const FacetPoint& s, Branch& b) {
  b.deta.clear();
  if (!b.p.interior) return;  // clamped on an end vertex: eta does not move
  const Vec2 r = s.x - b.p.y.x;
  for (int a = 0; a < ev.n(); ++a)
    for (int c = 0; c < 2; ++c) {
      b.deta.emplace_back(static_cast<PetscInt>(slave.nodes[a]) * 2 + c, -s.N[a] * b.p.y.dx[c] / b.p.F_eta);
      b.deta.emplace_back(static_cast<PetscInt>(b.facet->nodes[a]) * 2 + c,
                          -(-b.p.y.N[a] * b.p.y.dx[c] + b.p.y.dN[a] * r[c]) / b.p.F_eta);
    }
}

// The contact point of slave point s (one or two branches; none when no facet qualifies).
// Closest-point projection, with one exception (choice): where s projects into the interior
// of two master facets that share a vertex (the point lies on the concave side of that
// vertex: a concave master, or a convex one that s penetrates), the closest point jumps
// from one facet to the other halfway, and that jump makes the gap and B_ext discontinuous
// in u. There the contact point blends both projections, weighted by how far each lies from
// the shared vertex: w_b = s_b / (s_1 + s_2), s_b the parametric distance of branch b's
// projection from the vertex. Each branch reaches the vertex exactly where the other's
// projection leaves its facet (a segment cut), so the blend is continuous and smooth on
// every piece, and the Jacobian stays exact. Measured on hertz-cylinders-2d level 2 before
// this, lu-mumps: with single-threaded BLAS, step 2 hovered at residuals 1e-8 to 3e-7 for
// 20 iterations without a state change (and converged in 8 with threaded BLAS); a finite
// difference check of a penetrated level-0 state found errors of 1% in the master rows.
// dw0 receives d w_0 / du (w_1 = 1 - w_0) when derivatives are asked.
std::vector<Branch> contact_point(const FacetEvaluator& ev, const Facet& f, const FacetPoint& s,
                                  const std::vector<const Facet*>& candidates, const std::vector<double>& u,
                                  double search_radius, bool with_derivatives, std::map<PetscInt, double>& dw0) {
  std::vector<Branch> valid;
  for (const Facet* m : candidates) {
    Branch b;
    b.facet = m;
    b.p = project(ev, *m, s.x, u);
    if (!b.p.found || b.p.distance > search_radius) continue;
    if (outward_normal(f, s.dx).dot(outward_normal(*m, b.p.y.dx)) >= 0) continue;  // the master's back
    valid.push_back(std::move(b));
  }
  if (valid.empty()) return {};
  const auto closest = std::min_element(valid.begin(), valid.end(), [](const Branch& a, const Branch& b) {
    return a.p.distance < b.p.distance;
  });
  std::vector<Branch> out{*closest};
  const Branch* partner = nullptr;
  if (closest->p.interior)
    for (const Branch& b : valid)
      if (&b != &*closest && b.p.interior && shared_end(*b.facet, *closest->facet) >= 0 &&
          (!partner || b.p.distance < partner->p.distance))
        partner = &b;
  if (partner) out.push_back(*partner);
  for (Branch& b : out)
    if (with_derivatives) projection_derivative(ev, f, s, b);
  if (out.size() == 1) return out;
  // s_b = eta_b or 1 - eta_b: the distance from the shared vertex; ds_b = sign_b d eta_b.
  double dist[2], sign[2];
  for (int b = 0; b < 2; ++b) {
    const int end = shared_end(*out[b].facet, *out[1 - b].facet);
    sign[b] = end == 0 ? 1.0 : -1.0;
    dist[b] = end == 0 ? out[b].p.eta : 1 - out[b].p.eta;
  }
  const double total = dist[0] + dist[1];
  if (!(total > 0)) return {out[0]};
  out[0].weight = dist[0] / total, out[1].weight = dist[1] / total;
  if (with_derivatives) {
    // w_0 = s_0 / (s_0 + s_1): dw_0 = (s_1 ds_0 - s_0 ds_1) / (s_0 + s_1)^2.
    for (int b = 0; b < 2; ++b) {
      const double factor = (b == 0 ? dist[1] : -dist[0]) * sign[b] / (total * total);
      for (const auto& [dof, de] : out[b].deta) dw0[dof] += factor * de;
    }
  }
  return out;
}

// One slave quadrature point at parameter xi of facet f and its contact point: the gap
// vector r = x1 - y, the motions since the previous step (15)-(16), and per branch the
// master's motion and (with derivatives) its rate along eta. `branches` is empty when the
// point has no contact point.
struct PointKinematics {
  FacetPoint s;
  std::vector<Branch> branches;
  std::map<PetscInt, double> dw0;  // d w_0 / du of a blended point (w_1 = 1 - w_0)
  Vec2 r = Vec2::Zero(), slave_motion = Vec2::Zero(), master_motion = Vec2::Zero();
  std::vector<Vec2> branch_motion, branch_rate;
};

PointKinematics point_kinematics(const FacetEvaluator& ev, const Facet& f, double xi,
                                 const std::vector<const Facet*>& candidates, const std::vector<double>& u,
                                 const std::vector<double>& u_previous, double search_radius, bool with_derivatives) {
  PointKinematics p;
  p.s = ev.at(f, xi, u);
  p.branches = contact_point(ev, f, p.s, candidates, u, search_radius, with_derivatives, p.dw0);
  Vec2 y = Vec2::Zero();
  for (const Branch& b : p.branches) {
    p.branch_motion.push_back(ev.combine(*b.facet, b.p.y.N, u) - ev.combine(*b.facet, b.p.y.N, u_previous));
    if (with_derivatives)
      p.branch_rate.push_back(ev.combine(*b.facet, b.p.y.dN, u) - ev.combine(*b.facet, b.p.y.dN, u_previous));
    y += b.weight * b.p.y.x;
    p.master_motion += b.weight * p.branch_motion.back();
  }
  p.r = p.s.x - y;
  p.slave_motion = ev.combine(f, p.s.N, u) - ev.combine(f, p.s.N, u_previous);
  return p;
}

// Node i's share wphi = w phi_i of the point: G_i, S_i and, when asked, their derivatives.
void add_node_kinematics(const FacetEvaluator& ev, const Facet& f, const PointKinematics& p, double wphi,
                         bool with_derivatives, NodeKinematics& node) {
  node.G += lift(wphi * p.r);
  node.S += lift(wphi * (p.slave_motion - p.master_motion));
  if (!with_derivatives) return;
  for (int a = 0; a < ev.n(); ++a)
    for (int c = 0; c < 2; ++c) {
      const PetscInt slave_dof = static_cast<PetscInt>(f.nodes[a]) * 2 + c;
      accumulate(node.dG, slave_dof, Vec3(wphi * p.s.N[a] * Vec3::Unit(c)));
      accumulate(node.dS, slave_dof, Vec3(wphi * p.s.N[a] * Vec3::Unit(c)));
    }
  for (size_t bi = 0; bi < p.branches.size(); ++bi) {
    const Branch& b = p.branches[bi];
    const double wb = wphi * b.weight;
    for (int a = 0; a < ev.n(); ++a)
      for (int c = 0; c < 2; ++c) {
        const PetscInt master_dof = static_cast<PetscInt>(b.facet->nodes[a]) * 2 + c;
        accumulate(node.dG, master_dof, Vec3(-wb * b.p.y.N[a] * Vec3::Unit(c)));
        accumulate(node.dS, master_dof, Vec3(-wb * b.p.y.N[a] * Vec3::Unit(c)));
      }
    for (const auto& [dof, de] : b.deta) {
      accumulate(node.dG, dof, lift(-wb * de * b.p.y.dx));
      accumulate(node.dS, dof, lift(-wb * de * p.branch_rate[bi]));
    }
  }
  if (p.branches.size() == 2)
    for (const auto& [dof, dw] : p.dw0) {
      accumulate(node.dG, dof, lift(-wphi * dw * (p.branches[0].p.y.x - p.branches[1].p.y.x)));
      accumulate(node.dS, dof, lift(-wphi * dw * (p.branch_motion[0] - p.branch_motion[1])));
    }
}

// The constraint forces of node i's multiplier lam at the point: the slave carries +lambda,
// the master -lambda at the contact point (r_u -= B_int^T lambda - B_ext^T lambda), with the
// blocks -B^T (columns row0..) and d(-B^T lambda)/du when jacobian is not null.
void add_node_forces(const FacetEvaluator& ev, const Facet& f, const PointKinematics& p, double wphi,
                     const Vec3& lam, PetscInt row0, std::vector<double>& r_u, nonlinear::SparseEntries* jacobian) {
  for (int a = 0; a < ev.n(); ++a)
    for (int c = 0; c < 2; ++c) {
      const PetscInt slave_dof = static_cast<PetscInt>(f.nodes[a]) * 2 + c;
      r_u[static_cast<size_t>(slave_dof)] -= wphi * p.s.N[a] * lam[c];
      if (jacobian) jacobian->add(slave_dof, row0 + c, -wphi * p.s.N[a]);
    }
  for (size_t bi = 0; bi < p.branches.size(); ++bi) {
    const Branch& b = p.branches[bi];
    const double wb = wphi * b.weight, dw_sign = bi == 0 ? 1.0 : -1.0;  // d w_1 = -d w_0
    for (int a = 0; a < ev.n(); ++a)
      for (int c = 0; c < 2; ++c) {
        const PetscInt master_dof = static_cast<PetscInt>(b.facet->nodes[a]) * 2 + c;
        r_u[static_cast<size_t>(master_dof)] += wb * b.p.y.N[a] * lam[c];
        if (!jacobian) continue;
        jacobian->add(master_dof, row0 + c, wb * b.p.y.N[a]);
        if (lam[c] == 0) continue;
        for (const auto& [dof, de] : b.deta) jacobian->add(master_dof, dof, wb * b.p.y.dN[a] * lam[c] * de);
        for (const auto& [dof, dw] : p.dw0) jacobian->add(master_dof, dof, dw_sign * wphi * b.p.y.N[a] * lam[c] * dw);
      }
  }
}

}  // namespace

SurfaceContact::SurfaceContact(std::string name, const fem::FieldSpace& space, int slave_tag, int master_tag,
                               ContactSettings settings, double search_radius)
    : ContactPair(std::move(name), space, slave_tag, settings),
      space_(space),
      master_tag_(master_tag),
      search_radius_(search_radius) {
  if (space.dim() != 2)
    throw Error(fmt::format("contact '{}': a deformable master is implemented in 2D (plane strain) only; "
                            "use master = \"plane\" in 3D", this->name()));
  if (slave_tag == master_tag) throw Error(fmt::format("contact '{}': the master boundary is the slave boundary", this->name()));
  slave_facets_ = collect_facets(space, slave_tag);
  master_facets_ = collect_facets(space, master_tag);
  if (master_facets_.empty()) throw Error(fmt::format("contact '{}': the master boundary has no facets", this->name()));
  for (Facet& f : slave_facets_)
    for (int k = 0; k < 2; ++k) {
      const auto it = std::lower_bound(slave_.vertices.begin(), slave_.vertices.end(), f.vertex[k]);
      f.node_of_vertex[k] = static_cast<int>(it - slave_.vertices.begin());
    }
  if (!(search_radius_ > 0)) {
    search_radius_ = 0;
    for (const Facet& m : master_facets_) search_radius_ = std::max(search_radius_, 2 * std::hypot(m.E[0], m.E[1]));
  }
}

void SurfaceContact::nodal_normals(const std::vector<double>& u, bool with_derivatives,
                                   std::vector<NodeKinematics>& nodes) const {
  const FacetEvaluator ev(space_.kind(), space_.nodes_per_facet());
  const fem::QuadratureRule rule = fem::simplex_quadrature(1, 3);  // phi_i x' is quadratic
  std::vector<Vec2> m(nodes.size(), Vec2::Zero());
  std::vector<std::map<PetscInt, Vec2>> dm(with_derivatives ? nodes.size() : 0);
  for (const Facet& f : slave_facets_)
    for (int q = 0; q < rule.size(); ++q) {
      const double xi = rule.point(q)[0], w = rule.weights[q];
      const FacetPoint p = ev.at(f, xi, u);
      for (int k = 0; k < 2; ++k) {
        const int i = f.node_of_vertex[k];
        const double wphi = w * (k == 0 ? 1 - xi : xi);
        m[i] += wphi * outward_normal(f, p.dx);
        if (!with_derivatives) continue;
        for (int a = 0; a < ev.n(); ++a)
          for (int c = 0; c < 2; ++c)
            accumulate<Vec2>(dm[i], static_cast<PetscInt>(f.nodes[a]) * 2 + c, wphi * p.dN[a] * outward_normal(f, Vec2::Unit(c)));
      }
    }
  for (size_t i = 0; i < nodes.size(); ++i) {
    const double length = m[i].norm();
    const Vec2 n = -m[i] / length;  // from the master towards the slave
    nodes[i].n = lift(n);
    if (!with_derivatives) continue;
    const Eigen::Matrix2d P = (Eigen::Matrix2d::Identity() - n * n.transpose()) / length;
    for (const auto& [dof, column] : dm[i]) nodes[i].dn[dof] = lift(-P * column);
  }
}

void SurfaceContact::compute_kinematics(int, const std::vector<double>& u, const double* lambda,
                                        std::vector<double>* r_u, nonlinear::SparseEntries* jacobian, PetscInt offset,
                                        bool with_derivatives, std::vector<NodeKinematics>& nodes) const {
  const FacetEvaluator ev(space_.kind(), space_.nodes_per_facet());
  nodes.assign(slave_.n_nodes(), NodeKinematics{});
  nodal_normals(u, with_derivatives, nodes);
  std::vector<double> covered(slave_.n_nodes(), 0.0);  // integral of phi_i over projected points

  std::vector<std::pair<Box, int>> boxes;
  for (size_t m = 0; m < master_facets_.size(); ++m)
    boxes.emplace_back(facet_box(ev, master_facets_[m], u, 0.0), static_cast<int>(m));
  const bgi::rtree<std::pair<Box, int>, bgi::quadratic<16>> tree(boxes.begin(), boxes.end());

  const fem::QuadratureRule rule = fem::simplex_quadrature(1, 7);
  std::vector<std::pair<Box, int>> hits;
  for (const Facet& f : slave_facets_) {
    hits.clear();
    tree.query(bgi::intersects(facet_box(ev, f, u, search_radius_)), std::back_inserter(hits));
    std::vector<const Facet*> candidates;
    // Pieces of the slave facet on which the closest point moves smoothly: cut where the
    // projection crosses a master facet's end.
    std::vector<double> cuts{0.0, 1.0};
    for (const auto& hit : hits) {
      const Facet& m = master_facets_[hit.second];
      if (share_vertex(f, m)) continue;  // self-contact: a facet never touches its neighbour
      candidates.push_back(&m);
      for (int end = 0; end < 2; ++end) {
        const double xi = segment_break(ev, f, m, end, u);
        if (xi > 0 && xi < 1) cuts.push_back(xi);
      }
    }
    if (candidates.empty()) continue;
    std::sort(cuts.begin(), cuts.end());
    const double length = std::hypot(f.E[0], f.E[1]);
    for (size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
      const double lo = cuts[piece], hi = cuts[piece + 1];
      if (hi - lo < 1e-14) continue;
      for (int q = 0; q < rule.size(); ++q) {
        const double xi = lo + (hi - lo) * rule.point(q)[0], w = rule.weights[q] * (hi - lo) * length;
        const PointKinematics p =
            point_kinematics(ev, f, xi, candidates, u, u_previous_, search_radius_, with_derivatives);
        if (p.branches.empty()) continue;
        for (int k = 0; k < 2; ++k) {
          const int i = f.node_of_vertex[k];
          const double wphi = w * (k == 0 ? 1 - xi : xi);
          add_node_kinematics(ev, f, p, wphi, with_derivatives, nodes[i]);
          covered[i] += wphi;
          if (!r_u) continue;
          const Vec3 lam = lambda ? Vec3(lambda[2 * i], lambda[2 * i + 1], 0.0) : Vec3::Zero();
          add_node_forces(ev, f, p, wphi, lam, offset + static_cast<PetscInt>(i) * 2, *r_u, jacobian);
        }
      }
    }
  }
  for (int i = 0; i < slave_.n_nodes(); ++i) nodes[i].admissible = covered[i] > 0;
}

}  // namespace stiction::contact
