#include "contact/rigid_plane_contact.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>

#include "common/error.hpp"

namespace stiction::contact {

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

Vec3 to_vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

RigidPlaneContact::RigidPlaneContact(std::string name, const fem::FieldSpace& space, int slave_tag, RigidPlane plane,
                                     ContactSettings settings)
    : name_(std::move(name)),
      dim_(space.dim()),
      slave_(make_slave_surface(space, slave_tag, name_)),
      plane_(std::move(plane)),
      settings_(settings) {
  Vec3 n = to_vec(plane_.normal);
  if (dim_ == 2) n[2] = 0;
  if (!(n.norm() > 0)) throw Error(fmt::format("contact '{}': the plane normal is zero", name_));
  n.normalize();
  plane_.normal = {n[0], n[1], n[2]};
  if (settings_.friction < 0) throw Error(fmt::format("contact '{}': friction must be >= 0", name_));
  if (!(settings_.modulus > 0)) throw Error(fmt::format("contact '{}': modulus must be > 0", name_), ErrorKind::Internal);
  tolerances_.force = settings_.force_tolerance * settings_.modulus;
  state_.assign(slave_.n_nodes(), NodeState::Inactive);
  last_dlambda_t_.assign(slave_.n_nodes(), {0, 0, 0});
  r_t_.resize(slave_.n_nodes());
  for (int i = 0; i < slave_.n_nodes(); ++i)
    r_t_[i] = settings_.tangential_penalty * settings_.modulus / (slave_.local_size(i) * slave_.lumped_mass[i]);
  u_previous_.assign(space.n_dofs(), 0.0);
}

std::array<double, 3> RigidPlaneContact::plane_motion(int step) const {
  std::array<double, 3> d{0, 0, 0};
  if (plane_.motion && step > 0) plane_.motion(step, d.data());
  return d;
}

void RigidPlaneContact::begin_step(int step, const std::vector<double>& u) {
  u_previous_ = u;
  previous_step_ = step - 1;
}

std::array<double, 3> RigidPlaneContact::b_times(const std::vector<double>& v, int i) const {
  std::array<double, 3> out{0, 0, 0};
  for (int k = slave_.b_start[i]; k < slave_.b_start[i + 1]; ++k)
    for (int c = 0; c < dim_; ++c) out[c] += slave_.b_coef[k] * v[static_cast<size_t>(slave_.b_node[k]) * dim_ + c];
  return out;
}

double RigidPlaneContact::weighted_gap(int step, const std::vector<double>& u, int i) const {
  const auto bu = b_times(u, i), d = plane_motion(step);
  double g = 0;
  for (int c = 0; c < dim_; ++c)
    g += plane_.normal[c] * (slave_.first_moment[static_cast<size_t>(i) * dim_ + c] + bu[c] -
                             (plane_.point[c] + d[c]) * slave_.lumped_mass[i]);
  return g;
}

std::array<double, 3> RigidPlaneContact::weighted_slip(int step, const std::vector<double>& u, int i) const {
  const auto now = b_times(u, i), before = b_times(u_previous_, i);
  const auto d = plane_motion(step), d_prev = plane_motion(previous_step_);
  std::array<double, 3> g{0, 0, 0};
  for (int c = 0; c < dim_; ++c) g[c] = now[c] - before[c] - (d[c] - d_prev[c]) * slave_.lumped_mass[i];
  return g;
}

void RigidPlaneContact::evaluate(int step, const std::vector<double>& u, const double* lambda, std::vector<double>& r_u,
                                 double* r_c, nonlinear::SparseEntries* jacobian, PetscInt offset) const {
  const int d = dim_;
  const Vec3 n = to_vec(plane_.normal);
  const Mat3 I_t = Mat3::Identity() - n * n.transpose();
  const double mu = settings_.friction;
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    Vec3 lam = Vec3::Zero();
    for (int c = 0; c < d; ++c) lam[c] = lambda[i * d + c];
    const PetscInt row0 = offset + static_cast<PetscInt>(i) * d;
    // Constraint forces: the slave carries the traction +lambda, r_u -= B^T lambda.
    for (int k = slave_.b_start[i]; k < slave_.b_start[i + 1]; ++k) {
      const size_t dof0 = static_cast<size_t>(slave_.b_node[k]) * d;
      for (int c = 0; c < d; ++c) {
        r_u[dof0 + c] -= slave_.b_coef[k] * lam[c];
        if (jacobian) jacobian->add(static_cast<PetscInt>(dof0 + c), row0 + c, -slave_.b_coef[k]);
      }
    }
    Vec3 c_i;
    Mat3 dc_du = Mat3::Zero(), dc_dl = Mat3::Zero();  // d c_i / d(B du) and d c_i / d lambda_i
    if (state_[i] == NodeState::Inactive) {
      c_i = lam;
      dc_dl = Mat3::Identity();
    } else {
      const double gn = weighted_gap(step, u, i);
      const Vec3 gt = I_t * to_vec(weighted_slip(step, u, i));
      if (state_[i] == NodeState::Stick) {
        c_i = n * gn + gt;
        dc_du = n * n.transpose() + I_t;  // = I
      } else {
        const double lambda_n = n.dot(lam);
        const Vec3 lambda_t = I_t * lam;
        const Vec3 a = lambda_t - r_t_[i] * gt;
        const double a_norm = a.norm();
        Vec3 a_hat = Vec3::Zero();
        Mat3 K = Mat3::Zero();
        if (mu > 0 && a_norm > 1e-300) {
          a_hat = a / a_norm;
          K = mu * lambda_n * (Mat3::Identity() - a_hat * a_hat.transpose()) / a_norm;
        }
        c_i = n * gn + lambda_t - mu * lambda_n * a_hat;
        dc_du = n * n.transpose() + r_t_[i] * K * I_t;
        dc_dl = I_t - mu * a_hat * n.transpose() - K * I_t;
      }
    }
    for (int c = 0; c < d; ++c) r_c[i * d + c] = c_i[c];
    if (!jacobian) continue;
    for (int c = 0; c < d; ++c)
      for (int e = 0; e < d; ++e) {
        if (dc_dl(c, e) != 0) jacobian->add(row0 + c, row0 + e, dc_dl(c, e));
        if (dc_du(c, e) == 0) continue;
        for (int k = slave_.b_start[i]; k < slave_.b_start[i + 1]; ++k)
          jacobian->add(row0 + c, static_cast<PetscInt>(slave_.b_node[k]) * d + e, slave_.b_coef[k] * dc_du(c, e));
      }
  }
}

int RigidPlaneContact::update_states(int step, const std::vector<double>& u, const double* lambda,
                                     const double* dlambda) {
  const int d = dim_;
  const Vec3 n = to_vec(plane_.normal);
  const Mat3 I_t = Mat3::Identity() - n * n.transpose();
  int changes = 0;
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    Vec3 lam = Vec3::Zero(), dlam = Vec3::Zero();
    for (int c = 0; c < d; ++c) lam[c] = lambda[i * d + c], dlam[c] = dlambda[i * d + c];
    const Vec3 gt = I_t * to_vec(weighted_slip(step, u, i)), lambda_t = I_t * lam;
    NodeQuantities q;
    q.gn = weighted_gap(step, u, i);
    q.gt_norm = gt.norm();
    q.gt_dot_lt = gt.dot(lambda_t);
    q.lambda_n = n.dot(lam);
    q.lambda_t_norm = lambda_t.norm();
    StateTolerances tol = tolerances_;
    tol.gap = settings_.gap_tolerance * slave_.diameter * slave_.lumped_mass[i];
    const NodeState next = next_state(state_[i], q, settings_.friction, tol);
    // Adaptive r_t (Sec. 4.4): consecutive tangential corrections pointing the same way mean
    // r_t is too small (grow it), opposite ways mean it overshoots (shrink it).
    const Vec3 dt = I_t * dlam, last = to_vec(last_dlambda_t_[i]);
    if (state_[i] == NodeState::Slip && next == NodeState::Slip && dt.norm() > 0 && last.norm() > 0) {
      const double cosine = dt.dot(last) / (dt.norm() * last.norm());
      if (cosine > 0.8) r_t_[i] *= 20;
      if (cosine < 0.3) r_t_[i] /= 20;
    }
    last_dlambda_t_[i] = {dt[0], dt[1], dt[2]};
    if (next != state_[i]) ++changes;
    state_[i] = next;
  }
  return changes;
}

std::vector<char> RigidPlaneContact::states() const {
  std::vector<char> s(state_.size());
  for (size_t i = 0; i < s.size(); ++i) s[i] = static_cast<char>(state_[i]);
  return s;
}

void RigidPlaneContact::schur_mass(nonlinear::SparseEntries& out, PetscInt offset) const {
  const int d = dim_;
  const Vec3 n = to_vec(plane_.normal);
  const Mat3 nn = n * n.transpose();
  for (size_t k = 0; k < slave_.mass_v.size(); ++k) {
    const int i = slave_.mass_i[k], j = slave_.mass_j[k];
    if (state_[i] == NodeState::Inactive || state_[j] == NodeState::Inactive) continue;
    const bool both_stick = state_[i] == NodeState::Stick && state_[j] == NodeState::Stick;
    const Mat3 P = both_stick ? Mat3::Identity() : nn;  // Pi_i Pi_j
    for (int c = 0; c < d; ++c)
      for (int e = 0; e < d; ++e)
        if (P(c, e) != 0) out.add(offset + i * d + c, offset + j * d + e, slave_.mass_v[k] * P(c, e));
  }
}

nonlinear::ConstraintSummary RigidPlaneContact::summary(const double* lambda) const {
  nonlinear::ConstraintSummary s;
  s.name = name_;
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    if (state_[i] == NodeState::Inactive) ++s.inactive;
    if (state_[i] == NodeState::Stick) ++s.stick;
    if (state_[i] == NodeState::Slip) ++s.slip;
    for (int c = 0; c < dim_; ++c) s.force[c] += slave_.lumped_mass[i] * lambda[i * dim_ + c];
  }
  return s;
}

}  // namespace stiction::contact
