#include "contact/node_row.hpp"

#include <unsupported/Eigen/AutoDiff>

namespace stiction::contact {

namespace {

// Twelve independent inputs: n, G, S, lambda (three components each).
using Derivatives = Eigen::Matrix<double, 12, 1>;
using Dual = Eigen::AutoDiffScalar<Derivatives>;
using DualVec = Eigen::Matrix<Dual, 3, 1>;

DualVec seed(const Vec3& v, int first) {
  DualVec out;
  for (int c = 0; c < 3; ++c) out[c] = Dual(v[c], 12, first + c);
  return out;
}

}  // namespace

NodeRow node_row(NodeState state, const Vec3& n_value, const Vec3& G_value, const Vec3& S_value,
                 const Vec3& lambda_value, double mu, double r_t) {
  NodeRow row;
  if (state == NodeState::Inactive) {
    row.c = lambda_value;
    row.d_lambda = Mat3::Identity();
    return row;
  }
  const DualVec n = seed(n_value, 0), G = seed(G_value, 3), S = seed(S_value, 6), lambda = seed(lambda_value, 9);
  const Dual gn = n.dot(G);
  const DualVec gt = S - n * n.dot(S);
  DualVec c;
  if (state == NodeState::Stick) {
    c = n * gn + gt;
  } else {
    const Dual lambda_n = n.dot(lambda);
    const DualVec lambda_t = lambda - n * lambda_n;
    const DualVec a = lambda_t - gt * Dual(r_t);
    const Dual a_norm = sqrt(a.squaredNorm().value() > 0 ? a.squaredNorm() : Dual(1.0));
    // |a| = 0 (no tangential traction and no slip): the direction a^ is undefined and the
    // Coulomb term vanishes with mu lambda_n a^ set to zero.
    c = n * gn + lambda_t;
    if (mu > 0 && a.squaredNorm().value() > 1e-300) c -= a * (Dual(mu) * lambda_n / a_norm);
  }
  for (int k = 0; k < 3; ++k) {
    row.c[k] = c[k].value();
    const Derivatives& d = c[k].derivatives();
    for (int j = 0; j < 3; ++j) {
      row.d_normal(k, j) = d[j];
      row.d_gap(k, j) = d[3 + j];
      row.d_slip(k, j) = d[6 + j];
      row.d_lambda(k, j) = d[9 + j];
    }
  }
  return row;
}

NodeRow weighted_by_mass(NodeRow row, NodeState s, const Vec3& n, double m) {
  if (s == NodeState::Inactive) {
    row.c *= m, row.d_lambda *= m;
  } else if (s == NodeState::Slip) {
    const Mat3 Q = m * Mat3::Identity() + (1 - m) * n * n.transpose();
    row.d_normal = Q * row.d_normal + (1 - m) * (n.dot(row.c) * Mat3::Identity() + n * row.c.transpose());
    row.d_gap = Q * row.d_gap, row.d_slip = Q * row.d_slip, row.d_lambda = Q * row.d_lambda;
    row.c = Q * row.c;
  }
  return row;
}

NodeQuantities node_quantities(const Vec3& n, const Vec3& G, const Vec3& S, const Vec3& lambda) {
  const Vec3 gt = S - n * n.dot(S), lambda_t = lambda - n * n.dot(lambda);
  NodeQuantities q;
  q.gn = n.dot(G);
  q.gt_norm = gt.norm();
  q.gt_dot_lt = gt.dot(lambda_t);
  q.lambda_n = n.dot(lambda);
  q.lambda_t_norm = lambda_t.norm();
  return q;
}

}  // namespace stiction::contact
