#include "contact/contact_pair.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "common/error.hpp"
#include "fem/mesh_partition.hpp"

namespace stiction::contact {

double ContactSettings::friction_at(double t) const {
  if (friction_schedule.empty()) return friction;
  double mu = friction_schedule.front().second;
  for (const auto& [t_k, mu_k] : friction_schedule)
    if (t_k < t) mu = mu_k;
  return mu;
}

bool ContactSettings::frictional() const {
  if (friction_schedule.empty()) return friction > 0;
  for (const auto& [t_k, mu_k] : friction_schedule)
    if (mu_k > 0) return true;
  return false;
}

ContactPair::ContactPair(std::string name, const fem::FieldSpace& space, int slave_tag, ContactSettings settings)
    : dim_(space.dim()), slave_tag_(slave_tag), slave_(make_slave_surface(space, slave_tag, name)), settings_(settings), name_(std::move(name)) {
  if (settings_.friction < 0) throw Error(fmt::format("contact '{}': friction must be >= 0", name_));
  for (size_t k = 0; k < settings_.friction_schedule.size(); ++k) {
    const auto [t_k, mu_k] = settings_.friction_schedule[k];
    if (mu_k < 0) throw Error(fmt::format("contact '{}': friction must be >= 0 (row {} of its table)", name_, k + 1));
    if (k > 0 && !(t_k > settings_.friction_schedule[k - 1].first))
      throw Error(fmt::format("contact '{}': the friction table's times must increase (row {})", name_, k + 1));
  }
  if (!(settings_.modulus > 0)) throw Error(fmt::format("contact '{}': modulus must be > 0", name_), ErrorKind::Internal);
  tolerances_.force = settings_.force_tolerance * settings_.modulus;
  state_.assign(slave_.n_nodes(), NodeState::Inactive);
  last_dlambda_t_.assign(slave_.n_nodes(), Vec3::Zero());
  normals_.assign(slave_.n_nodes(), Vec3::Zero());
  slip_rows_.assign(slave_.n_nodes(), Mat3::Zero());
  r_t_.resize(slave_.n_nodes());
  for (int i = 0; i < slave_.n_nodes(); ++i) r_t_[i] = initial_r_t(i);
  u_previous_.assign(space.n_dofs(), 0.0);
  u_previous_n_app_ = u_previous_.size();
}

// The adaptive r_t (Sec. 4.3) starts every increment from its initial value, with no
// previous correction to compare with (choice: the paper says neither whether the adaptation
// carries over nor how far it may go). Carried over, it drifted without bound on ironing-2d
// level 0: by t = 1.045, after 9 sliding steps, r_t ranged over 1e-17 .. 1.6e5 times its
// initial value among the slipping nodes, and the sliding steps stalled (25 iterations,
// then down to 1/64 of a step, DIVERGED_MAX_ITERATIONS at t = 1.057).
void ContactPair::begin_increment(double t_start, fem::StateView u) {
  u_previous_.assign(u.storage().begin(), u.storage().end());
  u_previous_map_ = u.storage_map();
  u_previous_n_app_ = u.size();
  last_evaluated_.valid = false;  // the slip increments S_i are relative to u_previous_
  t_previous_ = t_start;
  for (int i = 0; i < slave_.n_nodes(); ++i) r_t_[i] = initial_r_t(i);
  std::fill(last_dlambda_t_.begin(), last_dlambda_t_.end(), Vec3::Zero());
  // Settled is a property of this increment's iterates: the new load moves the multipliers
  // again. Carried over from the last increment, it let a run's first increment after a
  // converged one linearise the normals at once while the same increment after a restart or
  // a cut-back (restore_state) did not, so a restarted run left the uninterrupted one's path.
  settled_ = false;
}

double ContactPair::initial_r_t(int i) const {
  return settings_.tangential_penalty * settings_.modulus / (slave_.local_size(i) * slave_.lumped_mass[i]);
}

// The states, one entry per node (r_t restarts with every increment).
std::vector<double> ContactPair::save_state() const {
  std::vector<double> out;
  for (NodeState s : state_) out.push_back(static_cast<double>(s));
  return out;
}

void ContactPair::restore_state(const std::vector<double>& saved) {
  const size_t n = state_.size();
  if (saved.size() != n)
    throw Error(fmt::format("contact '{}': a saved state of {} entries does not fit its {} slave nodes", name_,
                            saved.size(), n));
  for (size_t i = 0; i < n; ++i) state_[i] = static_cast<NodeState>(static_cast<int>(saved[i]));
  settled_ = false;
}

void ContactPair::evaluate(double t, fem::StateView u, const double* lambda, fem::ResidualView r_u,
                           double* r_c, nonlinear::SparseEntries* jacobian, PetscInt offset) const {
  if (jacobian) {
    std::vector<NodeKinematics> nodes;
    kinematics_everywhere(t, u, lambda, r_u, jacobian, offset, true, nodes);
    write_rows(t, nodes, lambda, r_c, jacobian, offset);
    return;
  }
  evaluate_kinematics(t, u, lambda, r_u, offset);
  write_rows(t, last_evaluated_.nodes, lambda, r_c, nullptr, offset);
}

void ContactPair::evaluate_kinematics(double t, fem::StateView u, const double* lambda,
                                      fem::ResidualView r_u, PetscInt offset) const {
  last_evaluated_.valid = false;
  kinematics_everywhere(t, u, lambda, r_u, nullptr, offset, false, last_evaluated_.nodes);
  last_evaluated_.t = t;
  last_evaluated_.u.assign(u.storage().begin(), u.storage().end());
  last_evaluated_.valid = true;
}

void ContactPair::distribute(MPI_Comm comm, const std::vector<char>& owned) {
  comm_ = comm;
  owned_.clear();
  if (!owned.empty())
    for (int i = 0; i < slave_.n_nodes(); ++i) owned_.push_back(owned[static_cast<size_t>(i) * dim_]);
  last_evaluated_.valid = false;
}

// Each process integrates what it owns: the per-node sums of its nodes and its share of the
// forces (compute_kinematics), which the caller sums over processes like the elastic
// residual (fem::GhostedVector::add_ghosts_to_owners); a node's kinematics come from its
// owner alone and are copied to every process.
void ContactPair::kinematics_everywhere(double t, fem::StateView u, const double* lambda,
                                        fem::ResidualView r_u, nonlinear::SparseEntries* jacobian,
                                        PetscInt offset, bool with_derivatives,
                                        std::vector<NodeKinematics>& nodes) const {
  compute_kinematics(t, u, lambda, r_u, jacobian, offset, with_derivatives, nodes);
  if (!distributed()) return;
  constexpr int kValues = 10;  // n, G, S, admissible
  std::vector<double> values(nodes.size() * kValues, 0.0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!owned_[i]) continue;
    double* v = &values[i * kValues];
    for (int c = 0; c < 3; ++c) v[c] = nodes[i].n[c], v[3 + c] = nodes[i].G[c], v[6 + c] = nodes[i].S[c];
    v[9] = nodes[i].admissible ? 1 : 0;
  }
  fem::sum_over_ranks(comm_, values);
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (owned_[i]) continue;
    const double* v = &values[i * kValues];
    for (int c = 0; c < 3; ++c) nodes[i].n[c] = v[c], nodes[i].G[c] = v[3 + c], nodes[i].S[c] = v[6 + c];
    nodes[i].admissible = v[9] != 0;
  }
}

void ContactPair::local_kinematics(double t, fem::StateView u, std::vector<NodeKinematics>& nodes) const {
  whole_ = true;
  try {
    compute_kinematics(t, u, nullptr, {}, nullptr, 0, false, nodes);
  } catch (...) {
    whole_ = false;
    throw;
  }
  whole_ = false;
}

void ContactPair::evaluate_rows(double t, fem::StateView u, const double* lambda, double* r_c) const {
  write_rows(t, kinematics_at(t, u), lambda, r_c, nullptr, 0);
}

const std::vector<NodeKinematics>& ContactPair::kinematics_at(double t, fem::StateView u) const {
  if (!at_last_evaluated(t, u)) evaluate_kinematics(t, u, nullptr, {}, 0);
  return last_evaluated_.nodes;
}

void ContactPair::write_rows(double t, const std::vector<NodeKinematics>& nodes, const double* lambda, double* r_c,
                             nonlinear::SparseEntries* jacobian, PetscInt offset) const {
  const int d = dim_;
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    const NodeKinematics& k = nodes[i];
    if (jacobian) normals_[i] = k.n;
    Vec3 lam = Vec3::Zero();
    for (int c = 0; c < d; ++c) lam[c] = lambda[i * d + c];
    // A node that lost its projection cannot press: it takes the inactive row until the
    // state machine releases it.
    const NodeState s = k.admissible ? state_[i] : NodeState::Inactive;
    NodeRow row = node_row(s, k.n, k.G, k.S, lam, settings_.friction_at(t), r_t_[i]);
    if (settings_.mass_weighted_rows) row = weighted_by_mass(row, s, k.n, slave_.lumped_mass[i]);
    for (int c = 0; c < d; ++c) r_c[i * d + c] = row.c[c];
    if (!jacobian) continue;
    slip_rows_[i] = s == NodeState::Slip ? row.d_slip : Mat3::Zero();
    if (!owns(i)) continue;  // its owner writes the row
    const PetscInt row0 = offset + static_cast<PetscInt>(i) * d;
    for (int c = 0; c < d; ++c)
      for (int e = 0; e < d; ++e)
        if (row.d_lambda(c, e) != 0) jacobian->add(row0 + c, row0 + e, row.d_lambda(c, e));
    if (s == NodeState::Inactive) continue;
    auto chain = [&](const Mat3& partial, const std::map<PetscInt, Vec3>& columns) {
      for (const auto& [dof, column] : columns) {
        const Vec3 v = partial * column;
        for (int c = 0; c < d; ++c)
          if (v[c] != 0) jacobian->add(row0 + c, dof, v[c]);
      }
    };
    using NL = ContactSettings::NormalLinearisation;
    if (settings_.normal_linearisation == NL::Exact || (settings_.normal_linearisation == NL::Settled && settled_))
      chain(row.d_normal, k.dn);
    chain(row.d_gap, k.dG);
    chain(row.d_slip, k.dS);
  }
}

int ContactPair::update_states(double t, fem::StateView u, const double* lambda, const double* dlambda) {
  const std::vector<NodeKinematics>& nodes = kinematics_at(t, u);
  const double entry = entry_depth(nodes);
  const int d = dim_;
  int changes = 0;
  // r_t adapts only while Newton still moves the multipliers (the update above
  // settle_tolerance of them). Closer in, the cosine of two consecutive corrections measures
  // linear-solve and round-off noise, not a drifting slip direction, and each factor of 20
  // changes the slip rows' equations: a^ of (19) depends on r_t until lambda_t and g_t are
  // exactly antiparallel. Adapting to the end, block-strips level 0 (lu-mumps, first sliding
  // step) reached a contact residual of 5e-7 with fixed states, then rose to 3e-4 as r_t
  // jumped, and failed after 25 iterations; with r_t held there it converged in 11.
  const bool adapt_r_t = !multipliers_settled(lambda, dlambda);
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    const NodeKinematics& k = nodes[i];
    normals_[i] = k.n;
    Vec3 lam = Vec3::Zero(), dlam = Vec3::Zero();
    for (int c = 0; c < d; ++c) lam[c] = lambda[i * d + c], dlam[c] = dlambda[i * d + c];
    StateTolerances tol = tolerances_;
    tol.gap = std::max(settings_.gap_tolerance * slave_.diameter, entry) * slave_.lumped_mass[i];
    NodeState next = next_state(state_[i], node_quantities(k.n, k.G, k.S, lam), settings_.friction_at(t), tol);
    if (!k.admissible) next = NodeState::Inactive;
    // Adaptive r_t (Sec. 4.3): consecutive tangential corrections pointing the same way mean
    // r_t is too small (grow it), opposite ways mean it overshoots (shrink it), but never
    // below tangential_penalty_floor times its start (choice; the paper sets no bound, but
    // warns that too small an r_t never aligns lambda_t). As r_t -> 0 the slip row
    // lambda_t = mu lambda_n a^ holds for any direction of lambda_t (a -> lambda_t): Newton
    // loses the friction's direction and the contact residual swings with the states fixed
    // (groove walls of block-strips). The default floor, one of the paper's factors of 20
    // below the start, leaves r_t room to fall where the start is too stiff (ironing-2d).
    // Measurements: docs/method.md, "Choices beyond the paper".
    const Vec3 dt = dlam - k.n * k.n.dot(dlam), last = last_dlambda_t_[i];
    if (adapt_r_t && state_[i] == NodeState::Slip && next == NodeState::Slip && dt.norm() > 0 && last.norm() > 0) {
      const double cosine = dt.dot(last) / (dt.norm() * last.norm());
      if (cosine > 0.8) r_t_[i] *= 20;
      if (cosine < 0.3) r_t_[i] = std::max(r_t_[i] / 20, settings_.tangential_penalty_floor * initial_r_t(i));
    }
    last_dlambda_t_[i] = dt;
    if (next != state_[i]) ++changes;
    state_[i] = next;
  }
  settled_ = changes == 0 && multipliers_settled(lambda, dlambda);
  return changes;
}

// Settled: no state changed, and the update moved the multipliers by at most
// settle_tolerance relative to them (Newton is then close, where the normals' terms buy
// the quadratic rate; far from it they of order p / h disturb Newton and Krylov alike).
// Held states count as unchanged: without this, the iterations the driver holds the states
// for converged only linearly (ironing-2d level 0, sliding: constraint residual falling
// 2.5x per iteration over five iterations until an update let the normals in).
bool ContactPair::multipliers_settled(const double* lambda, const double* dlambda) const {
  double step2 = 0, size2 = 0;
  for (int k = 0; k < slave_.n_nodes() * dim_; ++k) step2 += dlambda[k] * dlambda[k], size2 += lambda[k] * lambda[k];
  return step2 <= settings_.settle_tolerance * settings_.settle_tolerance * size2;
}

void ContactPair::states_held(const double* lambda, const double* dlambda) {
  settled_ = multipliers_settled(lambda, dlambda);
}

// Entering contact (choice): an inactive node enters contact only if it is penetrated at least
// a fraction f as deep as the deepest penetrated inactive node (the deepest always enters, so
// no penetration goes unanswered). PDAS corrects a too-narrow and a too-wide contact zone at
// different speeds: one solve adds every node a too-narrow zone lets penetrate, while a
// too-wide zone loses only its outermost node per solve, the one whose multiplier carries the
// edge tension. So the guess should err narrow. f is the depth below which Hertz's contact
// zone ends within the overlap of the undeformed bodies (overlap b^2 = 2 R delta for an
// approach delta): in 3D a^2 = R delta, so f = 1 - a^2/b^2 = 1/2; in plane strain
// a^2 = 4 R delta / (2 ln(4R/a) - 1), so f = 1 - 2 / (2 ln(4R/a) - 1), 0.76 at a = R/25
// (our Hertz scenes' load; smaller a gives larger f): 0.75 is used.
// Measured when the rule came in (before the blended contact point of surface_contact.cpp,
// self-contact-2d still in four load steps), lu-mumps, Newton iterations per load step at
// levels 0 / 1 / 2, every penetrated node entering -> this rule:
//   hertz-cylinder-2d   7+3 / 9+5 / 10+8    ->  1+3 / 1+3 / 1+3
//   hertz-cylinders-2d  9+5 / 12+7 / 14+10  ->  5+6 / 7+6 / 6+8
//   hertz-sphere-3d     4+3 / 6+5 (levels 0 / 1)  ->  1+3 / 2+4
//   self-contact-2d, steps 3+4: 7+11 / 8+12 / active-set cycle in step 4  ->  8+9 / 7+12 / 9+14
// and unchanged counts on contact-patch-2d and sliding-block-2d (uniform penetrations).
double ContactPair::entry_depth(const std::vector<NodeKinematics>& nodes) const {
  const double fraction = dim_ == 3 ? 0.5 : 0.75;
  double deepest = 0;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].admissible && state_[i] == NodeState::Inactive)
      deepest = std::max(deepest, -nodes[i].n.dot(nodes[i].G) / slave_.lumped_mass[i]);
  return fraction * deepest;
}

std::vector<double> ContactPair::mean_normal_gaps(double t, fem::StateView u) const {
  const std::vector<NodeKinematics>& nodes = kinematics_at(t, u);
  std::vector<double> gaps(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i)
    gaps[i] = nodes[i].admissible ? nodes[i].n.dot(nodes[i].G) / slave_.lumped_mass[i]
                                  : std::numeric_limits<double>::infinity();
  return gaps;
}

std::vector<int> ContactPair::multiplier_vertices() const {
  std::vector<int> out;
  for (int v : slave_.vertices) out.insert(out.end(), dim_, v);
  return out;
}

std::vector<nonlinear::MultiplierNode> ContactPair::nodes(double t, fem::StateView u,
                                                         const double* lambda) const {
  // Output may be written by one process: off the last evaluated point a distributed pair
  // evaluates every node here rather than call the other processes.
  std::vector<NodeKinematics> local;
  if (distributed() && !at_last_evaluated(t, u)) local_kinematics(t, u, local);
  const std::vector<NodeKinematics>& kin = local.empty() ? kinematics_at(t, u) : local;
  std::vector<nonlinear::MultiplierNode> out(slave_.n_nodes());
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    nonlinear::MultiplierNode& node = out[i];
    const int v = slave_.vertices[i];
    node.vertex = v;
    Vec3 lam = Vec3::Zero();
    for (int c = 0; c < dim_; ++c) {
      // Vertex v is node v of the space: its coefficients are its displacement.
      node.position[c] = slave_.reference_position[i][c] + u[static_cast<size_t>(v) * dim_ + c];
      lam[c] = lambda[i * dim_ + c];
    }
    const Vec3 n = kin[i].n;
    node.gap = kin[i].admissible ? n.dot(kin[i].G) / slave_.lumped_mass[i] : std::numeric_limits<double>::infinity();
    node.normal = n.dot(lam);
    const Vec3 lt = lam - n * node.normal;
    for (int c = 0; c < 3; ++c) node.multiplier[c] = lam[c], node.tangential[c] = lt[c];
    node.state = static_cast<char>(state_[i]);
  }
  return out;
}

std::vector<char> ContactPair::states() const {
  std::vector<char> s(state_.size());
  for (size_t i = 0; i < s.size(); ++i) s[i] = static_cast<char>(state_[i]);
  return s;
}

void ContactPair::describe_surface(nonlinear::MultiplierSurfaceEntries& out, PetscInt offset) const {
  const int d = dim_;
  auto add_per_component = [&](const std::vector<int>& rows, const std::vector<int>& cols,
                               const std::vector<double>& values, nonlinear::SparseEntries& to) {
    for (size_t k = 0; k < values.size(); ++k)
      for (int c = 0; c < d; ++c) to.add(offset + rows[k] * d + c, offset + cols[k] * d + c, values[k]);
  };
  add_per_component(slave_.mass_i, slave_.mass_j, slave_.mass_v, out.mass);
  add_per_component(slave_.stiffness_i, slave_.stiffness_j, slave_.stiffness_v, out.laplacian);
  auto add_block = [&](int i, const Mat3& block, nonlinear::SparseEntries& to) {
    for (int c = 0; c < d; ++c)
      for (int e = 0; e < d; ++e)
        if (block(c, e) != 0) to.add(offset + i * d + c, offset + i * d + e, block(c, e));
  };
  for (int i = 0; i < slave_.n_nodes(); ++i) {
    if (state_[i] == NodeState::Inactive) continue;
    const Vec3& n = normals_[i];
    add_block(i, state_[i] == NodeState::Stick ? Mat3::Identity() : Mat3(n * n.transpose()), out.projector);
    add_block(i, Mat3::Identity(), out.constrained);
    if (state_[i] == NodeState::Slip) add_block(i, slip_rows_[i], out.slip_rows);
  }
}

nonlinear::ConstraintSummary ContactPair::summary(const double* lambda) const {
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
