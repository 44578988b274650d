#include "contact/slave_surface.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

#include "common/error.hpp"
#include "fem/quadrature.hpp"

namespace stiction::contact {

double SlaveSurface::local_size(int i) const {
  return dim == 2 ? lumped_mass[i] : std::sqrt(lumped_mass[i]);
}

namespace {

// K of one flat P1 facet with edge vectors E (d x (d-1)), the chord of a curved one (K is a
// preconditioner's surface Laplacian on the multiplier): the hats' surface gradients are
// E (E^T E)^-1 e_j for the vertices 1..d-1 and minus their sum for vertex 0.
void add_surface_stiffness(const Eigen::MatrixXd& E, double measure, const int* mult, SlaveSurface& s) {
  const int d = static_cast<int>(E.rows()), sd = static_cast<int>(E.cols());
  Eigen::MatrixXd grads(d, d);
  grads.rightCols(sd) = E * (E.transpose() * E).inverse();
  grads.col(0) = -grads.rightCols(sd).rowwise().sum();
  const Eigen::MatrixXd K = measure * grads.transpose() * grads;
  for (int k = 0; k < d; ++k)
    for (int l = 0; l < d; ++l) {
      s.stiffness_i.push_back(mult[k]);
      s.stiffness_j.push_back(mult[l]);
      s.stiffness_v.push_back(K(k, l));
    }
}

}  // namespace

SlaveSurface make_slave_surface(const fem::FieldSpace& space, int facet_tag, const std::string& name) {
  const mesh::Mesh& mesh = space.mesh();
  const int d = space.dim(), sd = d - 1, npf = space.nodes_per_facet();
  SlaveSurface s;
  s.dim = d;
  std::map<int, int> node_of_vertex;
  std::vector<int> facets;
  for (int f = 0; f < mesh.n_facets(); ++f) {
    if (mesh.facet_tags[f] != facet_tag) continue;
    facets.push_back(f);
    for (int k = 0; k < d; ++k) node_of_vertex.emplace(mesh.facet(f)[k], 0);
  }
  if (facets.empty()) throw Error(fmt::format("contact '{}': the slave boundary has no facets", name));
  for (auto& [v, i] : node_of_vertex) {
    i = static_cast<int>(s.vertices.size());
    s.vertices.push_back(v);
    std::array<double, 3> X{0, 0, 0};
    std::copy(mesh.vertex(v), mesh.vertex(v) + d, X.begin());
    s.reference_position.push_back(X);
  }
  const int n = s.n_nodes();
  s.lumped_mass.assign(n, 0.0);
  s.first_moment.assign(static_cast<size_t>(n) * d, 0.0);

  // Degree 4: exact for phi_i N_a (degree 3) and phi_i phi_j X.
  const fem::QuadratureRule rule = fem::simplex_quadrature(sd, 4);
  std::vector<double> N(npf), dN(static_cast<size_t>(npf) * std::max(sd, 1));
  std::vector<std::map<int, double>> rows(n);
  std::vector<int> nodes(npf);
  std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (int f : facets) {
    const int* v = mesh.facet(f);
    space.facet_nodes(f, nodes.data());
    const double* X0 = mesh.vertex(v[0]);
    Eigen::MatrixXd E(d, sd);
    for (int j = 0; j < sd; ++j)
      for (int i = 0; i < d; ++i) E(i, j) = mesh.vertex(v[j + 1])[i] - X0[i];
    const double measure = std::sqrt((E.transpose() * E).determinant());
    int mult[3];
    for (int k = 0; k < d; ++k) mult[k] = node_of_vertex.at(v[k]);
    add_surface_stiffness(E, measure, mult, s);
    for (int k = 0; k < d; ++k)
      for (int i = 0; i < d; ++i) {
        lo[i] = std::min(lo[i], mesh.vertex(v[k])[i]);
        hi[i] = std::max(hi[i], mesh.vertex(v[k])[i]);
      }
    for (int q = 0; q < rule.size(); ++q) {
      const double* xi = rule.point(q);
      fem::eval_shape(sd, space.kind(), xi, N.data(), dN.data());
      double phi[3] = {1, 0, 0};  // P1 hats: barycentric coordinates
      for (int j = 0; j < sd; ++j) phi[0] -= xi[j], phi[j + 1] = xi[j];
      // The reference point and measure: chord map plus, on a curved P2 facet, its edge
      // nodes' offsets (fem/cell_geometry.hpp).
      double X[3] = {0, 0, 0};
      Eigen::MatrixXd J = E;
      for (int i = 0; i < d; ++i) {
        X[i] = X0[i];
        for (int j = 0; j < sd; ++j) X[i] += E(i, j) * xi[j];
      }
      for (int a = d; a < npf; ++a) {
        const double* g = space.node_offset(nodes[a]);
        for (int i = 0; i < d; ++i) {
          X[i] += g[i] * N[a];
          for (int j = 0; j < sd; ++j) J(i, j) += g[i] * dN[a * sd + j];
        }
      }
      const double w = rule.weights[q] * std::sqrt((J.transpose() * J).determinant());
      for (int k = 0; k < d; ++k) {
        const int i = mult[k];
        s.lumped_mass[i] += w * phi[k];
        for (int c = 0; c < d; ++c) s.first_moment[static_cast<size_t>(i) * d + c] += w * phi[k] * X[c];
        for (int a = 0; a < npf; ++a) rows[i][nodes[a]] += w * phi[k] * N[a];
        for (int l = 0; l < d; ++l) {
          s.mass_i.push_back(i);
          s.mass_j.push_back(mult[l]);
          s.mass_v.push_back(w * phi[k] * phi[l]);
        }
      }
    }
  }
  s.b_start.push_back(0);
  for (const auto& row : rows) {
    for (const auto& [node, coef] : row) {
      s.b_node.push_back(node);
      s.b_coef.push_back(coef);
    }
    s.b_start.push_back(static_cast<int>(s.b_node.size()));
  }
  double diag = 0;
  for (int i = 0; i < d; ++i) diag += (hi[i] - lo[i]) * (hi[i] - lo[i]);
  s.diameter = std::sqrt(diag);
  return s;
}

}  // namespace stiction::contact
