#pragma once
// Frictional contact of a deformable slave surface against a rigid plane (paper Sec. 4 with
// an analytic master: the ground of the block-with-strips scene). The plane moves rigidly
// (a translation per load step); its normal n points towards the slave body and is the
// contact normal of every node (the L2-projected master normal of a plane is n itself).
//
// Per slave node i (multiplier lambda_i, P1 on the slave surface, Cartesian components):
//   G_i = int phi_i (x1 - p(t))                               gn_i = n . G_i, weighted gap (13)
//   S_i = int phi_i [(x1 - x1^p) - (p(t) - p(t_prev))]        slip increment (15)
// and the rows of node_row.hpp. The slave carries the traction +lambda: r_u -= B_int^T lambda.
// G and S are linear in u with the constant derivative B_int (reference-surface integrals),
// and dn = 0, so the blocks of (30) are the exact Jacobian (checked in tests/unit/contact).
#include <array>
#include <functional>
#include <string>

#include "contact/contact_pair.hpp"
#include "fem/app_view.hpp"

namespace stiction::contact {

struct RigidPlane {
  std::array<double, 3> point{0, 0, 0};
  std::array<double, 3> normal{0, 1, 0};           // unit, towards the slave body
  std::function<void(double t, double* out)> motion;  // translation at pseudo-time t (0 at t = 0)
};

class RigidPlaneContact final : public ContactPair {
public:
  RigidPlaneContact(std::string name, const fem::FieldSpace& space, int slave_tag, RigidPlane plane,
                    ContactSettings settings);
  std::unique_ptr<nonlinear::MultiplierConstraint> over(const fem::FieldSpace& space) const override {
    return std::make_unique<RigidPlaneContact>(name(), space, slave_tag_, plane_, settings_);
  }

private:
  void compute_kinematics(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u,
                          nonlinear::SparseEntries* jacobian, PetscInt offset, bool with_derivatives,
                          std::vector<NodeKinematics>& nodes) const override;
  Vec3 b_times(fem::StateView v, int i) const;  // sum_a b_ia v_a
  Vec3 plane_motion(double t) const;

  RigidPlane plane_;
  Vec3 normal_;
};

}  // namespace stiction::contact
