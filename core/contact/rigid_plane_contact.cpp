#include "contact/rigid_plane_contact.hpp"

#include <fmt/format.h>

#include "common/error.hpp"

namespace stiction::contact {

namespace {

Vec3 to_vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

RigidPlaneContact::RigidPlaneContact(std::string name, const fem::FieldSpace& space, int slave_tag, RigidPlane plane,
                                     ContactSettings settings)
    : ContactPair(std::move(name), space, slave_tag, settings), plane_(std::move(plane)) {
  normal_ = to_vec(plane_.normal);
  if (dim_ == 2) normal_[2] = 0;
  if (!(normal_.norm() > 0)) throw Error(fmt::format("contact '{}': the plane normal is zero", this->name()));
  normal_.normalize();
}

Vec3 RigidPlaneContact::plane_motion(double t) const {
  Vec3 d = Vec3::Zero();
  if (plane_.motion && t > 0) plane_.motion(t, d.data());
  return d;
}

Vec3 RigidPlaneContact::b_times(fem::StateView v, int i) const {
  Vec3 out = Vec3::Zero();
  for (int k = slave_.b_start[i]; k < slave_.b_start[i + 1]; ++k)
    for (int c = 0; c < dim_; ++c) out[c] += slave_.b_coef[k] * v[static_cast<size_t>(slave_.b_node[k]) * dim_ + c];
  return out;
}

void RigidPlaneContact::compute_kinematics(double t, fem::StateView u, const double* lambda,
                                           fem::ResidualView r_u, nonlinear::SparseEntries* jacobian,
                                           PetscInt offset, bool with_derivatives,
                                           std::vector<NodeKinematics>& nodes) const {
  const int d = dim_;
  const Vec3 p = to_vec(plane_.point) + plane_motion(t);
  const Vec3 plane_slip = plane_motion(t) - plane_motion(t_previous_);
  nodes.assign(slave_.n_nodes(), NodeKinematics{});
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    if (!owns(i)) continue;  // distributed: node i's kinematics and forces come from its owner
    NodeKinematics& k = nodes[i];
    k.n = normal_;
    Vec3 moment = Vec3::Zero();
    for (int c = 0; c < d; ++c) moment[c] = slave_.first_moment[static_cast<size_t>(i) * d + c];
    k.G = moment + b_times(u, i) - p * slave_.lumped_mass[i];
    k.S = b_times(u, i) - b_times(u_previous(), i) - plane_slip * slave_.lumped_mass[i];
    const PetscInt row0 = offset + static_cast<PetscInt>(i) * d;
    for (int j = slave_.b_start[i]; j < slave_.b_start[i + 1]; ++j) {
      const PetscInt dof0 = static_cast<PetscInt>(slave_.b_node[j]) * d;
      for (int c = 0; c < d; ++c) {
        if (with_derivatives) k.dG[dof0 + c] = k.dS[dof0 + c] = slave_.b_coef[j] * Vec3::Unit(c);
        if (!r_u) continue;
        // Constraint forces: the slave carries the traction +lambda, r_u -= B^T lambda.
        r_u[static_cast<size_t>(dof0 + c)] -= slave_.b_coef[j] * lambda[i * d + c];
        if (jacobian) jacobian->add(dof0 + c, row0 + c, -slave_.b_coef[j]);
      }
    }
  }
}

}  // namespace stiction::contact
