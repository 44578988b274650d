#include "contact/surface_contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>
#include <cstdint>
#include <map>

#include "common/error.hpp"
#include "contact/facet_columns.hpp"
#include "contact/merged_entries.hpp"
#include "fem/quadrature.hpp"

namespace stiction::contact {

namespace {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using facets::FacetEvaluator;
using facets::FacetPoint;
using facets::Geometry;
using facets::Projection;
using Facet = SurfaceFacet;

template <int D>
using BoxPoint = bg::model::point<double, D, bg::cs::cartesian>;
template <int D>
using Box = bg::model::box<BoxPoint<D>>;

template <int D>
Vec3 lift(const Eigen::Matrix<double, D, 1>& v) {
  Vec3 out = Vec3::Zero();
  out.head<D>() = v;
  return out;
}

template <int D>
BoxPoint<D> box_point(const Eigen::Matrix<double, D, 1>& x) {
  if constexpr (D == 2) return BoxPoint<D>(x[0], x[1]);
  else return BoxPoint<D>(x[0], x[1], x[2]);
}

// Bounding box of a facet's Bezier control points, which hold the whole (curved) facet,
// widened by margin. 2D: the ends and 2 x(1/2) - (x(0) + x(1)) / 2; 3D: control_net.
template <int D>
Box<D> facet_box(const FacetEvaluator<D>& ev, const Facet& f, fem::StateView u, double margin) {
  using Vec = typename Geometry<D>::Vec;
  std::vector<Vec> points;
  if constexpr (D == 2) {
    using Param = typename Geometry<D>::Param;
    const Vec a = ev.at(f, Param(0.0), u).x, b = ev.at(f, Param(1.0), u).x;
    points = {a, b, Vec(2 * ev.at(f, Param(0.5), u).x - 0.5 * (a + b))};
  } else {
    for (const Eigen::Vector3d& p : ev.control_net(f, u)) points.push_back(p);
  }
  Vec lo = Vec::Constant(1e300), hi = -lo;
  for (const Vec& x : points) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  return Box<D>(box_point<D>((lo.array() - margin).matrix()), box_point<D>((hi.array() + margin).matrix()));
}

// The facets tagged `tag`, oriented outward by the cell vertex opposite each.
std::vector<Facet> collect_facets(const fem::FieldSpace& space, int tag) {
  const mesh::Mesh& mesh = space.mesh();
  const int d = mesh.dim;
  using Key = std::array<int, 3>;
  auto key_of = [d](const int* v) {
    Key k{v[0], v[1], d == 3 ? v[2] : -1};
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    if (k[1] > k[2] && k[2] >= 0) std::swap(k[1], k[2]);
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    return k;
  };
  std::vector<Facet> out;
  std::map<Key, int> opposite;  // sorted facet vertices -> interior vertex
  for (int f = 0; f < mesh.n_facets(); ++f) {
    if (mesh.facet_tags[f] != tag) continue;
    Facet F;
    F.n_vertices = d;
    std::copy(mesh.facet(f), mesh.facet(f) + d, F.vertex);
    F.nodes.resize(space.nodes_per_facet());
    space.facet_nodes(f, F.nodes.data());
    for (int c = 0; c < d; ++c) {
      F.X0[c] = mesh.vertex(F.vertex[0])[c];
      for (int k = 0; k + 1 < d; ++k) F.E[k][c] = mesh.vertex(F.vertex[k + 1])[c] - F.X0[c];
    }
    for (size_t a = d; a < F.nodes.size(); ++a) {
      const double* g = space.node_offset(F.nodes[a]);
      for (int c = 0; c < d; ++c) {
        F.offset[a - d][c] = g[c];
        F.curved = F.curved || g[c] != 0;
      }
    }
    opposite[key_of(F.vertex)] = -1;
    out.push_back(F);
  }
  for (int c = 0; c < mesh.n_cells(); ++c) {
    const int* v = mesh.cell(c);
    for (int skip = 0; skip <= d; ++skip) {
      int face[3], n = 0;
      for (int k = 0; k <= d; ++k)
        if (k != skip) face[n++] = v[k];
      auto it = opposite.find(key_of(face));
      if (it != opposite.end()) it->second = v[skip];
    }
  }
  for (Facet& F : out) {
    const int interior = opposite.at(key_of(F.vertex));
    if (interior < 0) throw Error("contact: a contact facet belongs to no cell", ErrorKind::Internal);
    Vec3 inward = Vec3::Zero(), normal = Vec3::Zero();
    for (int c = 0; c < d; ++c) inward[c] = mesh.vertex(interior)[c] - F.X0[c];
    if (d == 2) normal.head<2>() = facets::normal_of<2>(facets::reference_edges<2>(F));
    else normal = facets::normal_of<3>(facets::reference_edges<3>(F));
    F.outward = normal.dot(inward) < 0 ? 1.0 : -1.0;
  }
  return out;
}

bool share_vertex(const Facet& a, const Facet& b) {
  for (int i = 0; i < a.n_vertices; ++i)
    for (int j = 0; j < b.n_vertices; ++j)
      if (a.vertex[i] == b.vertex[j]) return true;
  return false;
}

// The end (0 or 1) of segment a that is a vertex of segment b, or -1 (2D).
int shared_end(const Facet& a, const Facet& b) {
  for (int e = 0; e < 2; ++e)
    if (a.vertex[e] == b.vertex[0] || a.vertex[e] == b.vertex[1]) return e;
  return -1;
}

// Slave parameter xi whose projection on segment m lands on m's end `end` (0 or 1), in 2D:
// (x1(xi) - y_e) . y'_e = 0. Returns NaN when the slave facet is parallel to that normal.
double segment_break(const FacetEvaluator<2>& ev, const Facet& slave, const Facet& m, int end,
                     fem::StateView u) {
  using Param = Geometry<2>::Param;
  const FacetPoint<2> ye = ev.at(m, Param(static_cast<double>(end)), u);
  double xi = 0.5;
  for (int it = 0; it < 30; ++it) {
    const FacetPoint<2> s = ev.at(slave, Param(xi), u);
    const double h = (s.x - ye.x).dot(ye.dx.col(0)), dh = s.dx.col(0).dot(ye.dx.col(0));
    if (!(std::abs(dh) > 1e-14 * s.dx.norm() * ye.dx.norm())) return std::nan("");
    const double step = h / dh;
    xi -= step;
    if (std::abs(step) < 1e-15) return xi;
  }
  return xi;
}

// One master facet's share of a contact point: its projection, its weight, and (with
// derivatives) d eta / du by the implicit function theorem on the projection equation.
template <int D>
struct Branch {
  const Facet* facet = nullptr;
  Projection<D> p;
  double weight = 1;
  std::vector<std::pair<PetscInt, typename Geometry<D>::Param>> deta;
};

// d eta / du of branch b at slave point s.
// Closest point: sensitivity dF / du, F_k = (x1 - y) . y_,k; the slave's nodes move x1,
// the master's move y and its tangents.
// Crossing of the slave normal nu = n1(xi) (unnormalised) through x1 (3D): d(eta, t) =
// -A^-1 dR with dR = d x1 + t d nu (slave nodes) or -d y (master nodes), facet_projection.hpp.
template <int D>
void projection_derivative(const FacetEvaluator<D>& ev, const Facet& slave, const FacetPoint<D>& s, Branch<D>& b) {
  using Vec = typename Geometry<D>::Vec;
  using Param = typename Geometry<D>::Param;
  constexpr int P = D - 1;
  b.deta.clear();
  const auto& y = b.p.y;
  if (!b.p.crossing) {
    if (b.p.sensitivity.isZero(0)) return;  // at a vertex: eta does not move
    const Vec r = s.x - y.x;
    for (int a = 0; a < ev.n(); ++a)
      for (int c = 0; c < D; ++c) {
        Param dF_slave, dF_master;
        for (int k = 0; k < P; ++k) {
          dF_slave[k] = s.N[a] * y.dx(c, k);
          dF_master[k] = -y.N[a] * y.dx(c, k) + y.dN_of(a)[k] * r[c];
        }
        b.deta.emplace_back(static_cast<PetscInt>(slave.nodes[a]) * D + c, b.p.sensitivity * dF_slave);
        b.deta.emplace_back(static_cast<PetscInt>(b.facet->nodes[a]) * D + c, b.p.sensitivity * dF_master);
      }
  } else {
    for (int a = 0; a < ev.n(); ++a)
      for (int c = 0; c < D; ++c) {
        const Vec dR_slave = s.N[a] * Vec::Unit(c) + b.p.t * facets::normal_variation<D>(slave, s.dx, s.dN_of(a), c);
        const Vec dR_master = -y.N[a] * Vec::Unit(c);
        b.deta.emplace_back(static_cast<PetscInt>(slave.nodes[a]) * D + c,
                            Param(-(b.p.ray_inverse * dR_slave).template head<P>()));
        b.deta.emplace_back(static_cast<PetscInt>(b.facet->nodes[a]) * D + c,
                            Param(-(b.p.ray_inverse * dR_master).template head<P>()));
      }
  }
}

template <int D>
using MasterTree = bgi::rtree<std::pair<Box<D>, int>, bgi::quadratic<16>>;

// 3D closest points: how many master facets, nearest box first, a slave point looks at (the
// search stops earlier at the first box farther than the nearest point found). Asking the
// R-tree for every facet in order kept a heap of the whole tree per point: 17% of a
// hertz-spheres-3d level-1 solve with lu-mumps.
constexpr unsigned kNearestMasterFacets = 16;

// Where to look for a slave facet's master points: 2D, the master facets whose boxes meet the
// slave facet's box widened by the search radius (listed: the segment cuts need them all);
// 3D, the R-tree itself, searched per point.
template <int D>
struct MasterCandidates {
  const MasterTree<D>* tree = nullptr;
  const std::vector<Facet>* master = nullptr;
  std::vector<const Facet*> listed;
  std::vector<std::pair<Box<D>, int>>* hits = nullptr;  // 3D: scratch for the per-point query
  bool closest_point = true;  // 3D: the closest point instead of the slave normal's crossing
};

// The valid master points of slave point s (farther than the search radius, off the facet
// or on the master's back: not valid). 2D: closest-point projections on every listed
// candidate (the blend looks for a partner of the closest). 3D: crossings of the slave
// normal on the facets whose boxes meet the normal's segment within the search radius; or,
// with master_point = "closest", closest points on the kNearestMasterFacets nearest boxes,
// stopping at the first box farther than the nearest point found, which no facet inside it
// can beat.
template <int D>
std::vector<Branch<D>> valid_projections(const FacetEvaluator<D>& ev, const Facet& f, const FacetPoint<D>& s,
                                         const MasterCandidates<D>& candidates, fem::StateView u,
                                         double search_radius) {
  std::vector<Branch<D>> valid;
  const typename Geometry<D>::Vec slave_normal = facets::outward_normal<D>(f, s.dx);
  auto consider = [&](const Facet* m) {
    Branch<D> b;
    b.facet = m;
    if constexpr (D == 2) b.p = facets::project(ev, *m, s.x, u);
    else b.p = candidates.closest_point ? facets::project(ev, *m, s.x, u)
                                        : facets::intersect<D>(ev, *m, s.x, slave_normal, u);
    if (!b.p.found || b.p.distance > search_radius) return;
    if (slave_normal.dot(facets::outward_normal<D>(*m, b.p.y.dx)) >= 0) return;  // the master's back
    valid.push_back(std::move(b));
  };
  if constexpr (D == 2) {
    for (const Facet* m : candidates.listed) consider(m);
  } else if (!candidates.closest_point) {
    // A valid crossing lies on the normal's segment of half-length search_radius around s, so
    // only facets whose boxes meet that segment can hold one. A point near a surface lies in
    // the boxes of several facets, and walking the nearest boxes in order cost more than the
    // projections (block-strips, hertz-spheres-3d).
    const typename Geometry<D>::Vec reach = search_radius * slave_normal.normalized();
    const bg::model::segment<BoxPoint<D>> line(box_point<D>(typename Geometry<D>::Vec(s.x - reach)),
                                               box_point<D>(typename Geometry<D>::Vec(s.x + reach)));
    std::vector<std::pair<Box<D>, int>>& hits = *candidates.hits;
    hits.clear();
    candidates.tree->query(bgi::intersects(line), std::back_inserter(hits));
    for (const auto& [box, m] : hits)
      if (!share_vertex(f, (*candidates.master)[m])) consider(&(*candidates.master)[m]);  // self-contact
  } else {
    const BoxPoint<D> x = box_point<D>(s.x);
    double closest = search_radius;
    const auto& tree = *candidates.tree;
    for (auto it = tree.qbegin(bgi::nearest(x, kNearestMasterFacets)); it != tree.qend(); ++it) {
      if (bg::distance(x, it->first) > closest) break;
      const Facet& m = (*candidates.master)[it->second];
      if (share_vertex(f, m)) continue;  // self-contact: a facet never touches its neighbour
      consider(&m);
      if (!valid.empty()) closest = std::min(closest, valid.back().p.distance);
    }
  }
  return valid;
}

// Weights of a 2D contact point blended from two branches on facets sharing a vertex
// (contact_point): s_b = eta_b or 1 - eta_b, the distance of branch b's projection from the
// shared vertex, w_b = s_b / (s_0 + s_1); ds_b = sign_b d eta_b.
void blend(std::vector<Branch<2>>& out, bool with_derivatives, std::map<PetscInt, double>& dw0) {
  double dist[2], sign[2];
  for (int b = 0; b < 2; ++b) {
    const int end = shared_end(*out[b].facet, *out[1 - b].facet);
    sign[b] = end == 0 ? 1.0 : -1.0;
    dist[b] = end == 0 ? out[b].p.eta[0] : 1 - out[b].p.eta[0];
  }
  const double total = dist[0] + dist[1];
  if (!(total > 0)) {
    out.resize(1);
    return;
  }
  out[0].weight = dist[0] / total, out[1].weight = dist[1] / total;
  if (!with_derivatives) return;
  // w_0 = s_0 / (s_0 + s_1): dw_0 = (s_1 ds_0 - s_0 ds_1) / (s_0 + s_1)^2.
  for (int b = 0; b < 2; ++b) {
    const double factor = (b == 0 ? dist[1] : -dist[0]) * sign[b] / (total * total);
    for (const auto& [dof, de] : out[b].deta) dw0[dof] += factor * de[0];
  }
}

// The contact point of slave point s (one or two branches; none when no facet qualifies).
// Closest-point projection, with one exception in 2D (choice): where s projects into the
// interior of two master facets that share a vertex (the point lies on the concave side of
// that vertex: a concave master, or a convex one that s penetrates), the closest point jumps
// from one facet to the other halfway, and that jump makes the gap and B_ext discontinuous
// in u. There the contact point blends both projections, weighted by how far each lies from
// the shared vertex: w_b = s_b / (s_1 + s_2), s_b the parametric distance of branch b's
// projection from the vertex. Each branch reaches the vertex exactly where the other's
// projection leaves its facet (a segment cut), so the blend is continuous and smooth on
// every piece, and the Jacobian stays exact. Measured on hertz-cylinders-2d level 2 before
// this, lu-mumps: with single-threaded BLAS, step 2 hovered at residuals 1e-8 to 3e-7 for
// 20 iterations without a state change (and converged in 8 with threaded BLAS); a finite
// difference check of a penetrated level-0 state found errors of 1% in the master rows.
// In 3D the blend would need weights over the two or more facets around an edge or vertex
// and cuts along projected edges; the master point is instead, by default, where the slave
// normal through s crosses the master, which is continuous across master edges, or with
// master_point = "closest" the closest point without a blend (surface_contact.hpp).
// This chooses the branches (the search); finish_branches completes them.
template <int D>
std::vector<Branch<D>> contact_point(const FacetEvaluator<D>& ev, const Facet& f, const FacetPoint<D>& s,
                                     const MasterCandidates<D>& candidates, fem::StateView u,
                                     double search_radius) {
  std::vector<Branch<D>> valid = valid_projections<D>(ev, f, s, candidates, u, search_radius);
  if (valid.empty()) return {};
  const auto closest = std::min_element(valid.begin(), valid.end(), [](const Branch<D>& a, const Branch<D>& b) {
    return a.p.distance < b.p.distance;
  });
  std::vector<Branch<D>> out{*closest};
  if constexpr (D == 2) {
    const Branch<D>* partner = nullptr;
    if (closest->p.interior)
      for (const Branch<D>& b : valid)
        if (&b != &*closest && b.p.interior && shared_end(*b.facet, *closest->facet) >= 0 &&
            (!partner || b.p.distance < partner->p.distance))
          partner = &b;
    if (partner) out.push_back(*partner);
  }
  return out;
}

// The branches' derivatives (when asked) and a blended 2D point's weights; dw0 receives
// d w_0 / du (w_1 = 1 - w_0) when derivatives are asked.
template <int D>
void finish_branches(const FacetEvaluator<D>& ev, const Facet& f, const FacetPoint<D>& s, std::vector<Branch<D>>& out,
                     bool with_derivatives, std::map<PetscInt, double>& dw0) {
  for (Branch<D>& b : out)
    if (with_derivatives) projection_derivative<D>(ev, f, s, b);
  if constexpr (D == 2)
    if (out.size() == 2) blend(out, with_derivatives, dw0);
}

// One slave quadrature point at parameter eta of facet f and its contact point: the gap
// vector r = x1 - y, the motions since the previous step (15)-(16), and per branch the
// master's motion and (with derivatives) its rate along eta. `branches` is empty when the
// point has no contact point.
template <int D>
struct PointKinematics {
  using Vec = typename Geometry<D>::Vec;
  FacetPoint<D> s;
  std::vector<Branch<D>> branches;
  std::map<PetscInt, double> dw0;  // d w_0 / du of a blended point (w_1 = 1 - w_0)
  Vec r = Vec::Zero(), slave_motion = Vec::Zero(), master_motion = Vec::Zero();
  std::vector<Vec> branch_motion;
  std::vector<typename Geometry<D>::Tangents> branch_rate;
};

// choose(s) gives the branches of slave point s (contact_point, or what a search found).
template <int D, class Choose>
PointKinematics<D> point_kinematics(const FacetEvaluator<D>& ev, const Facet& f, const typename Geometry<D>::Param& eta,
                                    const Choose& choose, fem::StateView u,
                                    fem::StateView u_previous, bool with_derivatives) {
  using Vec = typename Geometry<D>::Vec;
  PointKinematics<D> p;
  p.s = ev.at(f, eta, u);
  p.branches = choose(p.s);
  finish_branches<D>(ev, f, p.s, p.branches, with_derivatives, p.dw0);
  Vec y = Vec::Zero();
  for (const Branch<D>& b : p.branches) {
    p.branch_motion.push_back(ev.values(*b.facet, b.p.y, u) - ev.values(*b.facet, b.p.y, u_previous));
    if (with_derivatives)
      p.branch_rate.push_back(ev.gradients(*b.facet, b.p.y, u) - ev.gradients(*b.facet, b.p.y, u_previous));
    y += b.weight * b.p.y.x;
    p.master_motion += b.weight * p.branch_motion.back();
  }
  p.r = p.s.x - y;
  p.slave_motion = ev.values(f, p.s, u) - ev.values(f, p.s, u_previous);
  return p;
}

// Node i's share wphi = w phi_i of the point: G_i, S_i and, when asked, their derivatives
// (the columns of vertex k of the facet, into `columns`).
template <int D>
void add_node_kinematics(const FacetEvaluator<D>& ev, const Facet& f, const PointKinematics<D>& p, double wphi,
                         bool with_derivatives, NodeKinematics& node, int k, FacetColumns& columns) {
  using Vec = typename Geometry<D>::Vec;
  node.G += lift<D>(wphi * p.r);
  node.S += lift<D>(wphi * (p.slave_motion - p.master_motion));
  if (!with_derivatives) return;
  for (int a = 0; a < ev.n(); ++a)
    for (int c = 0; c < D; ++c) {
      const Vec3 column = wphi * p.s.N[a] * Vec3::Unit(c);
      columns.add(k, static_cast<PetscInt>(f.nodes[a]) * D + c, column, column);
    }
  for (size_t bi = 0; bi < p.branches.size(); ++bi) {
    const Branch<D>& b = p.branches[bi];
    const double wb = wphi * b.weight;
    for (int a = 0; a < ev.n(); ++a)
      for (int c = 0; c < D; ++c) {
        const Vec3 column = -wb * b.p.y.N[a] * Vec3::Unit(c);
        columns.add(k, static_cast<PetscInt>(b.facet->nodes[a]) * D + c, column, column);
      }
    for (const auto& [dof, de] : b.deta)
      columns.add(k, dof, lift<D>(Vec(-wb * (b.p.y.dx * de))), lift<D>(Vec(-wb * (p.branch_rate[bi] * de))));
  }
  if (p.branches.size() == 2)
    for (const auto& [dof, dw] : p.dw0)
      columns.add(k, dof, lift<D>(Vec(-wphi * dw * (p.branches[0].p.y.x - p.branches[1].p.y.x))),
                  lift<D>(Vec(-wphi * dw * (p.branch_motion[0] - p.branch_motion[1]))));
}

// The constraint forces of node i's multiplier lam at the point: the slave carries +lambda,
// the master -lambda at the contact point (r_u -= B_int^T lambda - B_ext^T lambda), with the
// blocks -B^T (columns row0..) when jacobian is not null. The forces' variation with the
// master point is added once per point (add_force_variation).
template <int D>
void add_node_forces(const FacetEvaluator<D>& ev, const Facet& f, const PointKinematics<D>& p, double wphi,
                     const Vec3& lam, PetscInt row0, fem::ResidualView r_u, MergedEntries* jacobian) {
  for (int a = 0; a < ev.n(); ++a)
    for (int c = 0; c < D; ++c) {
      const PetscInt slave_dof = static_cast<PetscInt>(f.nodes[a]) * D + c;
      r_u[static_cast<size_t>(slave_dof)] -= wphi * p.s.N[a] * lam[c];
      if (jacobian) jacobian->add(slave_dof, row0 + c, -wphi * p.s.N[a]);
    }
  for (const Branch<D>& b : p.branches) {
    const double wb = wphi * b.weight;
    for (int a = 0; a < ev.n(); ++a)
      for (int c = 0; c < D; ++c) {
        const PetscInt master_dof = static_cast<PetscInt>(b.facet->nodes[a]) * D + c;
        r_u[static_cast<size_t>(master_dof)] += wb * b.p.y.N[a] * lam[c];
        if (jacobian) jacobian->add(master_dof, row0 + c, wb * b.p.y.N[a]);
      }
  }
}

// d(-B^T lambda)/du through the master point: the master's shape functions move with eta
// (and, for a blended 2D point, with the weights). Linear in lambda, so it takes the
// point's weighted multiplier lam_w = sum_i w phi_i lambda_i once instead of once per node:
// a third of the entries in 3D (where it was most of the contact Jacobian's entries).
template <int D>
void add_force_variation(const FacetEvaluator<D>& ev, const PointKinematics<D>& p, const Vec3& lam_w,
                         MergedEntries& jacobian) {
  for (size_t bi = 0; bi < p.branches.size(); ++bi) {
    const Branch<D>& b = p.branches[bi];
    const double dw_sign = bi == 0 ? 1.0 : -1.0;  // d w_1 = -d w_0
    for (int a = 0; a < ev.n(); ++a) {
      const Eigen::Map<const typename Geometry<D>::Param> dN_a(b.p.y.dN_of(a));
      for (int c = 0; c < D; ++c) {
        if (lam_w[c] == 0) continue;
        const PetscInt master_dof = static_cast<PetscInt>(b.facet->nodes[a]) * D + c;
        for (const auto& [dof, de] : b.deta) jacobian.add(master_dof, dof, b.weight * dN_a.dot(de) * lam_w[c]);
        for (const auto& [dof, dw] : p.dw0) jacobian.add(master_dof, dof, dw_sign * b.p.y.N[a] * lam_w[c] * dw);
      }
    }
  }
}

// Integration points (eta, weight per unit reference-simplex measure) on slave facet f.
// 2D: Gauss on each piece between the cuts where the projections of the candidates' ends
// land (the closest point moves smoothly on each piece). 3D: the triangle split into four
// at its edge midpoints, a degree-4 rule on each (surface_contact.hpp).
template <int D>
std::vector<std::pair<typename Geometry<D>::Param, double>> integration_points(
    const FacetEvaluator<D>& ev, const Facet& f, const MasterCandidates<D>& candidates,
    fem::StateView u) {
  using Param = typename Geometry<D>::Param;
  std::vector<std::pair<Param, double>> points;
  if constexpr (D == 2) {
    static const fem::QuadratureRule rule = fem::simplex_quadrature(1, 7);
    std::vector<double> cuts{0.0, 1.0};
    for (const Facet* m : candidates.listed)
      for (int end = 0; end < 2; ++end) {
        const double xi = segment_break(ev, f, *m, end, u);
        if (xi > 0 && xi < 1) cuts.push_back(xi);
      }
    std::sort(cuts.begin(), cuts.end());
    for (size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
      const double lo = cuts[piece], hi = cuts[piece + 1];
      if (hi - lo < 1e-14) continue;
      for (int q = 0; q < rule.size(); ++q)
        points.emplace_back(Param(lo + (hi - lo) * rule.point(q)[0]), rule.weights[q] * (hi - lo));
    }
  } else {
    static const fem::QuadratureRule rule = fem::simplex_quadrature(2, 4);
    // The four halved triangles: corner + the edges (e0, e1) / 2 of each.
    const Param corner[4] = {Param(0, 0), Param(0.5, 0), Param(0, 0.5), Param(0.5, 0.5)};
    const double orientation[4] = {1, 1, 1, -1};  // the middle one is flipped
    for (int t = 0; t < 4; ++t)
      for (int q = 0; q < rule.size(); ++q) {
        const Param xi(rule.point(q)[0], rule.point(q)[1]);
        points.emplace_back(corner[t] + 0.5 * orientation[t] * xi, rule.weights[q] / 4);
      }
  }
  return points;
}

}  // namespace

SurfaceContact::SurfaceContact(std::string name, const fem::FieldSpace& space, int slave_tag, int master_tag,
                               ContactSettings settings, double search_radius)
    : ContactPair(std::move(name), space, slave_tag, settings),
      space_(space),
      master_tag_(master_tag),
      requested_search_radius_(search_radius),
      search_radius_(search_radius) {
  if (space.dim() != 2 && space.dim() != 3)
    throw Error(fmt::format("contact '{}': a deformable master needs a 2D or 3D mesh", this->name()));
  if (slave_tag == master_tag) throw Error(fmt::format("contact '{}': the master boundary is the slave boundary", this->name()));
  slave_facets_ = collect_facets(space, slave_tag);
  master_facets_ = collect_facets(space, master_tag);
  if (master_facets_.empty()) throw Error(fmt::format("contact '{}': the master boundary has no facets", this->name()));
  for (Facet& f : slave_facets_)
    for (int k = 0; k < f.n_vertices; ++k) {
      const auto it = std::lower_bound(slave_.vertices.begin(), slave_.vertices.end(), f.vertex[k]);
      f.node_of_vertex[k] = static_cast<int>(it - slave_.vertices.begin());
    }
  if (!(search_radius_ > 0)) {
    search_radius_ = 0;
    for (const Facet& m : master_facets_)
      for (int k = 0; k + 1 < m.n_vertices; ++k) {
        const Vec3 e(m.E[k][0], m.E[k][1], m.E[k][2]);
        search_radius_ = std::max(search_radius_, 2 * e.norm());
        if (k == 1) search_radius_ = std::max(search_radius_, 2 * (e - Vec3(m.E[0][0], m.E[0][1], m.E[0][2])).norm());
      }
  }
}

template <int D>
void SurfaceContact::nodal_normals(fem::StateView u, const std::vector<char>& derive,
                                   std::vector<NodeKinematics>& nodes) const {
  using G = Geometry<D>;
  using Vec = typename G::Vec;
  constexpr int P = G::P;
  const FacetEvaluator<D> ev(space_.kind(), space_.nodes_per_facet());
  const fem::QuadratureRule rule = fem::simplex_quadrature(P, 3);  // phi_i |x,0 x x,1| is cubic
  std::vector<Vec> m(nodes.size(), Vec::Zero());
  std::vector<std::map<PetscInt, Vec>> dm(nodes.size());
  for (const Facet& f : slave_facets_) {
    if (!evaluated_here(f)) continue;
    for (int q = 0; q < rule.size(); ++q) {
      const typename G::Param eta = Eigen::Map<const typename G::Param>(rule.point(q));
      const FacetPoint<D> p = ev.at(f, eta, u);
      const Vec normal = facets::outward_normal<D>(f, p.dx);
      for (int k = 0; k < D; ++k) {
        const int i = f.node_of_vertex[k];
        const double wphi = rule.weights[q] * facets::vertex_hat<D>(k, eta);
        m[i] += wphi * normal;
        if (!derive[i]) continue;
        for (int a = 0; a < ev.n(); ++a)
          for (int c = 0; c < D; ++c)
            add_column<Vec>(dm[i], static_cast<PetscInt>(f.nodes[a]) * D + c,
                            wphi * facets::normal_variation<D>(f, p.dx, p.dN_of(a), c));
      }
    }
  }
  for (size_t i = 0; i < nodes.size(); ++i) {
    const double length = m[i].norm();
    const Vec n = -m[i] / length;  // from the master towards the slave
    nodes[i].n = lift<D>(n);
    if (!derive[i]) continue;
    const Eigen::Matrix<double, D, D> Pn = (Eigen::Matrix<double, D, D>::Identity() - n * n.transpose()) / length;
    for (const auto& [dof, column] : dm[i]) nodes[i].dn[dof] = lift<D>(Vec(-Pn * column));
  }
}

bool SurfaceContact::evaluated_here(const Facet& f) const {
  for (int k = 0; k < dim_; ++k)
    if (owns(f.node_of_vertex[k])) return true;
  return false;
}

bool SurfaceContact::adds_forces(const Facet& f) const { return owns(f.node_of_vertex[0]); }

void SurfaceContact::compute_kinematics(double t, fem::StateView u, const double* lambda,
                                        fem::ResidualView r_u, nonlinear::SparseEntries* jacobian, PetscInt offset,
                                        bool with_derivatives, std::vector<NodeKinematics>& nodes) const {
  if (dim_ == 2) kinematics<2>(t, u, lambda, r_u, jacobian, offset, with_derivatives, nodes);
  else kinematics<3>(t, u, lambda, r_u, jacobian, offset, with_derivatives, nodes);
}

template <int D>
void SurfaceContact::kinematics(double t, fem::StateView u, const double* lambda,
                                fem::ResidualView r_u, nonlinear::SparseEntries* jacobian, PetscInt offset,
                                bool with_derivatives, std::vector<NodeKinematics>& nodes) const {
  using Param = typename Geometry<D>::Param;
  const FacetEvaluator<D> ev(space_.kind(), space_.nodes_per_facet());
  nodes.assign(slave_.n_nodes(), NodeKinematics{});
  // Derivatives only where the Jacobian reads them: an inactive node's row (c = lambda) does
  // not depend on u, so its G, S and n need none. A facet needs the master point's
  // derivatives when one of its nodes is in contact or carries a multiplier (the forces'
  // variation). Far from contact most of a self-contact surface is inactive (the groove walls
  // of block-strips), and the derivative maps were most of its assembly time.
  std::vector<char> derive(slave_.n_nodes(), 0);
  if (with_derivatives)
    for (int i = 0; i < slave_.n_nodes(); ++i) derive[i] = owns(i) && state(i) != NodeState::Inactive;
  auto facet_derives = [&](const Facet& f) {
    if (!with_derivatives) return false;
    for (int k = 0; k < D; ++k) {
      const int i = f.node_of_vertex[k];
      if (derive[i]) return true;
      if (lambda)
        for (int c = 0; c < D; ++c)
          if (lambda[D * i + c] != 0) return true;
    }
    return false;
  };
  nodal_normals<D>(u, derive, nodes);
  std::vector<double> covered(slave_.n_nodes(), 0.0);  // integral of phi_i over projected points

  // The Jacobian at the last evaluated iterate replays that evaluation's search; an
  // evaluation without derivatives records its own.
  const bool replay = with_derivatives && found_.valid && at_last_evaluated(t, u);
  const bool record = !with_derivatives && recording();
  if (record) {
    found_ = SearchRecord{};
    found_.facet_points.assign(slave_facets_.size() + 1, 0);
    found_.searched.assign(slave_facets_.size(), 0);
  }
  // The branches the record holds for a point (slave point s of facet f), rebuilt.
  const auto replayed_branches = [&](const Facet& f, const FacetPoint<D>& s, const FoundPoint& found) {
    const typename Geometry<D>::Vec normal = facets::outward_normal<D>(f, s.dx);
    std::vector<Branch<D>> out(found.n_branches);
    for (int b = 0; b < found.n_branches; ++b) {
      const FoundBranch& fb = found_.branches[found.first_branch + b];
      out[b].facet = &master_facets_[fb.facet];
      out[b].p = facets::projection_at<D>(ev, *out[b].facet, s.x, normal, u, fb.crossing, fb.face,
                                          Eigen::Map<const Param>(fb.eta), fb.t);
    }
    return out;
  };
  const auto record_point = [&](const Param& eta, double weight, const std::vector<Branch<D>>& branches) {
    found_.points.push_back(
        {{0, 0}, weight, static_cast<int>(found_.branches.size()), static_cast<int>(branches.size())});
    Eigen::Map<Param>(found_.points.back().eta) = eta;
    for (const Branch<D>& b : branches) {
      found_.branches.push_back(
          {static_cast<int>(b.facet - master_facets_.data()), b.p.crossing, b.p.face, {0, 0}, b.p.t});
      Eigen::Map<Param>(found_.branches.back().eta) = b.p.eta;
    }
  };
  std::vector<std::pair<Box<D>, int>> boxes;
  if (!replay)
    for (size_t m = 0; m < master_facets_.size(); ++m)
      boxes.emplace_back(facet_box<D>(ev, master_facets_[m], u, 0.0), static_cast<int>(m));
  const MasterTree<D> tree(boxes.begin(), boxes.end());

  std::vector<std::pair<Box<D>, int>> hits;
  MergedEntries facet_entries;
  FacetColumns facet_columns(with_derivatives ? static_cast<int>(u.size()) : 0);
  for (size_t k = 0; k < slave_facets_.size(); ++k) {
    const Facet& f = slave_facets_[k];
    if (record) found_.facet_points[k] = static_cast<int>(found_.points.size());
    if (!evaluated_here(f)) continue;
    const bool forces_here = r_u && adds_forces(f);
    MasterCandidates<D> candidates{&tree, &master_facets_, {}, &hits,
                                   settings_.master_point == ContactSettings::MasterPoint::Closest};
    std::vector<std::pair<Param, double>> points;
    if (replay) {
      if (!found_.searched[k]) continue;
      for (int q = found_.facet_points[k]; q < found_.facet_points[k + 1]; ++q)
        points.emplace_back(Eigen::Map<const Param>(found_.points[q].eta), found_.points[q].weight);
    } else {
      const Box<D> near = facet_box<D>(ev, f, u, search_radius_);
      if constexpr (D == 2) {
        hits.clear();
        tree.query(bgi::intersects(near), std::back_inserter(hits));
        for (const auto& [box, m] : hits)  // self-contact: a facet never touches its neighbour
          if (!share_vertex(f, master_facets_[m])) candidates.listed.push_back(&master_facets_[m]);
        if (candidates.listed.empty()) continue;
      } else if (tree.qbegin(bgi::intersects(near)) == tree.qend()) {
        continue;
      }
      points = integration_points<D>(ev, f, candidates, u);
      if (record) found_.searched[k] = 1;
    }
    const bool derive_f = facet_derives(f);
    for (size_t q = 0; q < points.size(); ++q) {
      const auto& [eta, weight] = points[q];
      const auto choose = [&](const FacetPoint<D>& s) {
        return replay ? replayed_branches(f, s, found_.points[found_.facet_points[k] + q])
                      : contact_point<D>(ev, f, s, candidates, u, search_radius_);
      };
      const PointKinematics<D> p = point_kinematics<D>(ev, f, eta, choose, u, u_previous(), derive_f);
      if (record) record_point(eta, weight, p.branches);
      if (p.branches.empty()) continue;
      const double jacobian_f = ev.reference_measure(f, p.s);
      Vec3 lam_w = Vec3::Zero();
      for (int k = 0; k < D; ++k) {
        const int i = f.node_of_vertex[k];
        const double wphi = weight * jacobian_f * facets::vertex_hat<D>(k, eta);
        if (owns(i)) add_node_kinematics<D>(ev, f, p, wphi, derive_f && derive[i], nodes[i], k, facet_columns);
        covered[i] += wphi;
        if (!forces_here) continue;
        Vec3 lam = Vec3::Zero();
        if (lambda)
          for (int c = 0; c < D; ++c) lam[c] = lambda[D * i + c];
        lam_w += wphi * lam;
        add_node_forces<D>(ev, f, p, wphi, lam, offset + static_cast<PetscInt>(i) * D, r_u,
                           jacobian ? &facet_entries : nullptr);
      }
      if (forces_here && jacobian && derive_f) add_force_variation<D>(ev, p, lam_w, facet_entries);
    }
    if (derive_f)
      facet_columns.flush(D, [&](int k) {
        const int i = f.node_of_vertex[k];
        return owns(i) && derive[i] ? &nodes[i] : nullptr;
      });
    if (jacobian) facet_entries.flush_into(*jacobian);
  }
  if (record) {
    found_.facet_points.back() = static_cast<int>(found_.points.size());
    found_.valid = true;
  }
  for (int i = 0; i < slave_.n_nodes(); ++i) nodes[i].admissible = covered[i] > 0;
}

}  // namespace stiction::contact
