#pragma once
// Frictional contact of a deformable slave surface against a rigid plane (paper Sec. 4 with
// an analytic master: the ground of the block-with-strips scene). The plane moves rigidly
// (a translation per load step); its outward normal n points towards the slave body and is
// the contact normal of every node (the L2-projected master normal of a plane is n itself).
//
// Per slave node i (multiplier lambda_i, P1 on the slave surface, Cartesian components):
//   gn_i = int phi_i (x1 - p(t)) . n                              weighted gap (13)
//   g_i  = int phi_i [(x1 - x1^p) - (p(t) - p(t_prev))]           slip increment (15)
//   gt_i = (I - n n^T) g_i,  lambda_n = n . lambda_i,  lambda_t = (I - n n^T) lambda_i
// and the row c_i of (30) by state:
//   inactive  c_i = lambda_i                                        (R_SC lambda = 0)
//   stick     c_i = n gn_i + gt_i                                   (R_A: no slip)
//   slip      c_i = n gn_i + lambda_t - mu lambda_n a / |a|,  a = lambda_t - r_t gt_i   (19)
// The traction on the slave is +lambda (so lambda_n >= 0 presses), r_u -= B^T lambda, and
// friction opposes the slip: lambda_t = -mu lambda_n gt / |gt| while sliding (17)-(18).
//
// Sign of the augmentation (choice): (19) as printed, lambda_t = -mu lambda_n a/|a| with
// a = lambda_t + r_t gt, is consistent only while r_t |gt| > mu lambda_n (otherwise it asks
// lambda_t to point against itself). Written as the projection of lambda_t - r_t gt on the
// Coulomb disc (Alart & Curnier), the slip row is consistent for every r_t > 0, and r_t only
// steers the Newton path (adapted as in Sec. 4.4).
//
// Linearisation of the slip row (the paper's (23) is garbled; derived here, states and r_t
// frozen): with K = mu lambda_n (I - a^ a^T) / |a|,
//   d c_i = n (n . B du) + r_t K I_t B du + (I_t - mu a^ n^T - K I_t) d lambda_i
// "I_t" is the paper's diagonal term, "mu a^ n^T" its elongation E^C by d lambda_n, and
// K I_t (B du) its angular correction I^perp_t B_t. For a plane the normal does not vary,
// so these blocks are the exact Jacobian (checked against finite differences in tests).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "contact/contact_state.hpp"
#include "contact/slave_surface.hpp"
#include "nonlinear/multiplier_constraint.hpp"

namespace stiction::contact {

struct RigidPlane {
  std::array<double, 3> point{0, 0, 0};
  std::array<double, 3> normal{0, 1, 0};           // unit, towards the slave body
  std::function<void(int step, double* out)> motion;  // translation at a load step (0 at step 0)
};

struct ContactSettings {
  double friction = 0;             // Coulomb coefficient mu
  double modulus = 1;              // stiffness scale of the slave body (Young's modulus)
  double gap_tolerance = 1e-9;     // relative to the slave surface's diameter
  double force_tolerance = 1e-9;   // relative to the modulus
  double tangential_penalty = 1;   // r_t at the start, in units of E / (h_i m_i)
};

class RigidPlaneContact final : public nonlinear::MultiplierConstraint {
public:
  RigidPlaneContact(std::string name, const fem::FieldSpace& space, int slave_tag, RigidPlane plane,
                    ContactSettings settings);

  std::string name() const override { return name_; }
  int n_multipliers() const override { return slave_.n_nodes() * dim_; }
  void begin_step(int step, const std::vector<double>& u) override;
  void evaluate(int step, const std::vector<double>& u, const double* lambda, std::vector<double>& r_u, double* r_c,
                nonlinear::SparseEntries* jacobian, PetscInt offset) const override;
  int update_states(int step, const std::vector<double>& u, const double* lambda, const double* dlambda) override;
  std::vector<char> states() const override;
  void schur_mass(nonlinear::SparseEntries& out, PetscInt offset) const override;
  nonlinear::ConstraintSummary summary(const double* lambda) const override;

  const SlaveSurface& slave() const { return slave_; }
  NodeState state(int node) const { return state_[node]; }
  void set_state(int node, NodeState s) { state_[node] = s; }  // for tests

  // Weighted gap gn_i and slip increment g_i of node i at displacement u (step `step`).
  double weighted_gap(int step, const std::vector<double>& u, int i) const;
  std::array<double, 3> weighted_slip(int step, const std::vector<double>& u, int i) const;

private:
  std::array<double, 3> b_times(const std::vector<double>& v, int i) const;  // sum_a b_ia v_a
  std::array<double, 3> plane_motion(int step) const;

  std::string name_;
  int dim_;
  SlaveSurface slave_;
  RigidPlane plane_;
  ContactSettings settings_;
  StateTolerances tolerances_;
  std::vector<NodeState> state_;
  std::vector<double> r_t_;
  std::vector<std::array<double, 3>> last_dlambda_t_;
  std::vector<double> u_previous_;  // converged displacement of the previous load step
  int previous_step_ = 0;
};

}  // namespace stiction::contact
