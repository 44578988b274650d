#pragma once
// What every contact pair shares (paper Sec. 4): the slave surface with its P1 vector
// multiplier, the per-node contact states and their state machine (Sec. 4.5), the adaptive
// tangential penalty r_t (Sec. 4.3), the constraint rows of (30) (node_row.hpp) and the
// mass part of the Schur approximation (32). A master (rigid plane, deformable surface)
// supplies only its kinematics: per slave node the contact normal n_i, the vector weighted
// gap G_i and the weighted slip increment S_i with their derivatives, and the constraint
// forces -B^T lambda on the displacement equations.
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "contact/contact_state.hpp"
#include "contact/node_row.hpp"
#include "contact/slave_surface.hpp"
#include "fem/app_view.hpp"
#include "nonlinear/multiplier_constraint.hpp"

namespace stiction::contact {

struct ContactSettings {
  double friction = 0;             // Coulomb coefficient mu
  // Friction that changes with the load phase: rows (t_k, mu_k) with increasing t_k; an
  // increment ending at pseudo-time t uses mu_k of the last row with t_k < t (the first
  // row's before it), so a row at the end of a phase takes effect in the next. Empty: mu
  // is `friction` throughout.
  std::vector<std::pair<double, double>> friction_schedule;
  double friction_at(double t) const;
  bool frictional() const;  // mu > 0 at some time of the run
  double modulus = 1;              // stiffness scale of the slave body (Young's modulus)
  double gap_tolerance = 1e-9;     // relative to the slave surface's diameter
  double force_tolerance = 1e-9;   // relative to the modulus
  double tangential_penalty = 1;   // r_t at the start, in units of E / (h_i m_i)
  double tangential_penalty_floor = 1.0 / 20;  // smallest r_t, relative to the start's (choice: contact_pair.cpp)
  // How the Jacobian treats the variation of the nodal normals (a deformable master's
  // slave normals move with u; a rigid plane's do not, so its Jacobian is exact anyway):
  //   Exact    always linearised (exact Newton);
  //   Dropped  never, as the paper (Sec. 4.3, term (1) of (23)): a quasi-Newton step;
  //   Settled  linearised once an update changed no contact state and moved the multipliers
  //            by at most settle_tolerance relative to them (default, choice).
  // Measured with `stiction solve <scene> --level L --solver schur-amg` (the scene's
  // normal_linearisation key set; the other tolerances by a rebuild), Newton iterations per
  // load step and Krylov iterations per linear solve at levels 0 / 1 / 2:
  //   hertz-cylinders-2d   Dropped                 7+8 / 7+9 / 9+10,   8.4 /  9.0 /  9.4
  //                        Settled, tolerance inf  5+6 / 7+6 / 8+6,    14.3 / 17.8 / 22.4
  //                        Settled, 0.1            5+6 / 5+6 / 6+8,    11.4 / 13.8 / 18.9
  //                        Settled, 0.01 (default) 5+6 / 5+6 / 6+8,    10.5 / 11.9 / 14.3
  //                        Settled, 0.001          5+6 / 6+6 / 6+7,     9.1 /  9.7 / 10.8
  //                        Exact fails at every level (level 0: the active set cycles in
  //                        step 2 while the residual grows to 1e1; also with lu-mumps)
  //   self-contact-2d      Dropped needs up to 22 iterations in the last step, fails at 2;
  //                        Settled inf 3+3+3+6+7+5 / ..+6 / 3+3+3+7+9+6; 0.01 3+3+3+6+7+6 /
  //                        ..+7 / 3+3+3+6+9+7; 0.001 fails at level 2; Exact fails at 1, 2.
  // The normals' terms are of order p / h and S~ (32) does not model them (with the exact
  // S_g the Krylov count stays near 9.5), hence the Krylov growth when they enter early.
  enum class NormalLinearisation { Exact, Dropped, Settled };
  NormalLinearisation normal_linearisation = NormalLinearisation::Settled;
  double settle_tolerance = 1e-2;  // Settled: largest |d lambda| / |lambda| of a settled update
  // The rows of a released node (lambda = 0) and the tangential rows of a slipping node are
  // in traction units, the gap rows and the force rows of the displacement block in
  // traction x area (3D) or x length (2D); with true those traction rows are multiplied by
  // the node's lumped mass m_i (node_row.hpp: weighted_by_mass), so every row of the right
  // side carries forces. Off by default (choice, measured at level 1 with schur-amg, Newton
  // iterations and Krylov per solve without -> with): hertz-cylinders-2d 11, 10.2 -> 10,
  // 13.7; hertz-sphere-3d 8, 20.6 -> 5, 30.0; sliding-block-2d 13, 18.8 -> 12, 21.5;
  // hertz-spheres-3d, where the traction rows outweighed the forces by up to 1e5, the active
  // set cycled in step 2 -> 10, 28.5 (hertz-spheres-3d sets it; holding each block of the
  // right side to the Krylov tolerance instead, removed after 433c5b4, gave 12, 65.3).
  bool mass_weighted_rows = false;
  // The master point x2 of a slave point x1 on a deformable master (surface_contact.hpp):
  //   Closest         the closest point (paper Sec. 4.1); the only rule in 2D;
  //   NormalCrossing  where the slave facet's normal through x1 crosses the master (3D
  //                   default, choice: the closest point jumps across the edges of a
  //                   curved master, and Newton fails on hertz-spheres-3d with it).
  enum class MasterPoint { Closest, NormalCrossing };
  MasterPoint master_point = MasterPoint::NormalCrossing;  // 2D pairs ignore it (Closest)
};

// Kinematics of one slave node at a displacement u. The derivative maps hold, per
// displacement unknown k, the column d(.)/du_k (filled only when derivatives are asked).
struct NodeKinematics {
  Vec3 n = Vec3::Zero(), G = Vec3::Zero(), S = Vec3::Zero();
  bool admissible = true;  // false: no valid projection; the node cannot be in contact
  std::map<PetscInt, Vec3> dn, dG, dS;
};

class ContactPair : public nonlinear::MultiplierConstraint {
public:
  ContactPair(std::string name, const fem::FieldSpace& space, int slave_tag, ContactSettings settings);

  std::string name() const override { return name_; }
  int n_multipliers() const override { return slave_.n_nodes() * dim_; }
  std::vector<int> multiplier_vertices() const override;
  void begin_increment(double t_start, fem::StateView u) override;
  void evaluate(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u, double* r_c,
                nonlinear::SparseEntries* jacobian, PetscInt offset) const override;
  void evaluate_rows(double t, fem::StateView u, const double* lambda, double* r_c) const override;
  int update_states(double t, fem::StateView u, const double* lambda, const double* dlambda) override;
  void states_held(const double* lambda, const double* dlambda) override;
  std::vector<char> states() const override;
  void distribute(MPI_Comm comm, const std::vector<char>& owned) override;
  void describe_surface(nonlinear::MultiplierSurfaceEntries& out, PetscInt offset) const override;
  nonlinear::ConstraintSummary summary(const double* lambda) const override;
  std::vector<nonlinear::MultiplierNode> nodes(double t, fem::StateView u,
                                              const double* lambda) const override;
  std::vector<double> save_state() const override;
  void restore_state(const std::vector<double>& saved) override;
  std::vector<std::pair<std::string, int>> surfaces() const override { return {{"slave", slave_tag_}}; }

  // Mean normal gap of each slave node at u, gn_i / m_i (a length; negative: penetration),
  // +infinity at nodes without a projection on the master.
  std::vector<double> mean_normal_gaps(double t, fem::StateView u) const;

  const SlaveSurface& slave() const { return slave_; }
  const ContactSettings& settings() const { return settings_; }
  NodeState state(int node) const { return state_[node]; }
  void set_state(int node, NodeState s) { state_[node] = s; }  // for tests

protected:
  // The master's part: kinematics of every slave node at u (with derivatives when asked; an
  // implementation may leave them out at inactive nodes, whose rows do not read them)
  // and, when r_u is not empty, the constraint forces r_u -= B^T lambda (with the blocks
  // -B^T and d(-B^T lambda)/du added to jacobian when it is not null). Distributed
  // (owns below), only the kinematics of the nodes this process owns count, and each part
  // of the forces must be added by one process: the pair shares the owned nodes'
  // kinematics over the processes, and the caller sums the forces.
  virtual void compute_kinematics(double t, fem::StateView u, const double* lambda,
                                  fem::ResidualView r_u, nonlinear::SparseEntries* jacobian, PetscInt offset,
                                  bool with_derivatives, std::vector<NodeKinematics>& nodes) const = 0;

  // (t, u) is the point of the last evaluation without derivatives (whose kinematics
  // kinematics_at keeps): a master may reuse what it found there, and must record what it
  // finds in an evaluation without derivatives unless recording() is false.
  bool recording() const { return !whole_; }
  bool at_last_evaluated(double t, fem::StateView u) const {
    return last_evaluated_.valid && last_evaluated_.t == t && std::ranges::equal(last_evaluated_.u, u.storage());
  }

  // Whether this process evaluates slave node i as its own: every node on one process, and
  // in an evaluation for this process alone (local_kinematics).
  bool owns(int i) const { return whole_ || owned_.empty() || owned_[i]; }
  bool distributed() const { return !owned_.empty() && !whole_; }

  int dim_;
  int slave_tag_;
  SlaveSurface slave_;
  ContactSettings settings_;
  // Converged state at the start of the increment: a copy of the storage of the view
  // begin_increment was given, addressed as that view was (u_previous()).
  std::vector<double> u_previous_;
  const int* u_previous_map_ = nullptr;
  std::size_t u_previous_n_app_ = 0;
  fem::StateView u_previous() const {
    return {u_previous_.data(), u_previous_.size(), u_previous_map_, u_previous_n_app_};
  }
  double t_previous_ = 0;           // its pseudo-time

private:
  // r_t of node i at the start of an increment: tangential_penalty E / (h_i m_i).
  double initial_r_t(int i) const;
  // The mean penetration depth an inactive node must exceed to enter contact at this update:
  // a fraction of the deepest penetrated inactive node's.
  double entry_depth(const std::vector<NodeKinematics>& nodes) const;
  // The kinematics at (t, u) without derivatives, from the last evaluation when it was made
  // at the same point: a Newton iteration evaluates its iterate (the step's residual), then
  // updates the states and writes the rows of the new states there, and each evaluation of
  // a deformable master searches it for every slave quadrature point.
  // Distributed, every process must call it at the same points (a new point is evaluated
  // together).
  const std::vector<NodeKinematics>& kinematics_at(double t, fem::StateView u) const;
  // Evaluates the kinematics without derivatives at (t, u) (and the forces into r_u when not
  // empty) and keeps them as the last evaluated point's.
  void evaluate_kinematics(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u,
                           PetscInt offset) const;
  // compute_kinematics, then, distributed, each owned node's kinematics (without
  // derivatives) copied to every process (the forces stay each process's share).
  void kinematics_everywhere(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u,
                             nonlinear::SparseEntries* jacobian, PetscInt offset, bool with_derivatives,
                             std::vector<NodeKinematics>& nodes) const;
  // Every node's kinematics at (t, u) computed on this process alone, without collective
  // calls (for output that one process writes), leaving the last evaluation's as they are.
  void local_kinematics(double t, fem::StateView u, std::vector<NodeKinematics>& nodes) const;
  // Writes r_c (and, with jacobian, the owned rows of C_u and C_l) from the nodes' kinematics.
  void write_rows(double t, const std::vector<NodeKinematics>& nodes, const double* lambda, double* r_c,
                  nonlinear::SparseEntries* jacobian, PetscInt offset) const;

  std::string name_;
  MPI_Comm comm_ = MPI_COMM_SELF;
  std::vector<char> owned_;  // per slave node; empty: all (one process)
  mutable bool whole_ = false;  // inside local_kinematics
  StateTolerances tolerances_;
  std::vector<NodeState> state_;
  std::vector<double> r_t_;
  std::vector<Vec3> last_dlambda_t_;
  // Normals at the last iterate evaluated with its Jacobian (for describe_surface, which the
  // Newton driver calls right after assembling that Jacobian) or updated on.
  mutable std::vector<Vec3> normals_;
  // d c_i / d S_i of every slipping node's row at that iterate (zero elsewhere).
  mutable std::vector<Mat3> slip_rows_;
  // The kinematics of the last evaluation without derivatives and the point (t, u) it was
  // made at (a copy of u: one displacement vector per pair).
  struct EvaluatedPoint {
    bool valid = false;
    double t = 0;
    std::vector<double> u;  // the state's storage (fem::AppView::storage)
    std::vector<NodeKinematics> nodes;
  };
  mutable EvaluatedPoint last_evaluated_;
  // The last update changed no state (or held them) and moved the multipliers by at most
  // settle_tolerance relative to them.
  bool settled_ = false;
  bool multipliers_settled(const double* lambda, const double* dlambda) const;
};

}  // namespace stiction::contact
