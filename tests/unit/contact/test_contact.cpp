// Contact against a rigid plane: the blocks of (30) are the derivatives of the contact
// residual (finite differences, states frozen), and the state machine's transitions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "contact/rigid_plane_contact.hpp"
#include "scene/scene.hpp"

namespace stiction::contact {
namespace {

const char* kBlockOnPlane = R"(
[[material]]
name = "m"
model = "linear"
E = 2.0
nu = 0.3

[[body]]
name = "block"
material = "m"
mesh = { generator = "structured-box", size = [1.0, 1.0, 0.5], cells = [2, 2, 1] }

[[contact]]
boundary = "zmin"
master = "plane"
point = [0.0, 0.0, -0.01]
normal = [0.1, 0.0, 1.0]
motion = [0.02, 0.01, 0.005]
friction = 0.4
)";

// Every entry of the contact blocks against central differences of (r_u, r_c), with a mix
// of inactive, sticking and slipping nodes and a tilted, moving plane.
TEST(RigidPlaneContact, JacobianMatchesFiniteDifferences) {
  auto s = scene::build_scene(kBlockOnPlane, "block-on-plane", ".");
  auto& pair = dynamic_cast<RigidPlaneContact&>(*s->contacts.at(0));
  const int n_u = s->space->n_dofs(), n_l = pair.n_multipliers(), n = n_u + n_l;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<double> u0(n_u), u(n_u), lambda(n_l);
  for (double& v : u0) v = 0.01 * U(rng);
  for (double& v : u) v = 0.02 * U(rng);
  for (int i = 0; i < pair.slave().n_nodes(); ++i) {
    pair.set_state(i, static_cast<NodeState>(i % 3));
    for (int c = 0; c < 3; ++c) lambda[3 * i + c] = U(rng) + (c == 2 ? 2.0 : 0.0);  // lambda_n > 0
  }
  pair.begin_step(1, u0);
  auto residual = [&](const std::vector<double>& uu, const std::vector<double>& ll, std::vector<double>& out) {
    std::vector<double> ru(n_u, 0.0), rc(n_l, 0.0);
    pair.evaluate(1, uu, ll.data(), ru, rc.data(), nullptr, n_u);
    out = ru;
    out.insert(out.end(), rc.begin(), rc.end());
  };
  nonlinear::SparseEntries J;
  {
    std::vector<double> ru(n_u, 0.0), rc(n_l, 0.0);
    pair.evaluate(1, u, lambda.data(), ru, rc.data(), &J, n_u);
  }
  std::vector<double> dense(static_cast<size_t>(n) * n, 0.0);
  for (size_t k = 0; k < J.size(); ++k) dense[static_cast<size_t>(J.rows[k]) * n + J.cols[k]] += J.values[k];
  double max_entry = 0, max_error = 0;
  const double h = 1e-6;
  std::vector<double> rp, rm;
  for (int j = 0; j < n; ++j) {
    auto up = u, um = u;
    auto lp = lambda, lm = lambda;
    if (j < n_u) up[j] += h, um[j] -= h;
    else lp[j - n_u] += h, lm[j - n_u] -= h;
    residual(up, lp, rp);
    residual(um, lm, rm);
    for (int i = 0; i < n; ++i) {
      const double fd = (rp[i] - rm[i]) / (2 * h), an = dense[static_cast<size_t>(i) * n + j];
      max_entry = std::max(max_entry, std::abs(an));
      max_error = std::max(max_error, std::abs(fd - an));
    }
  }
  EXPECT_GT(max_entry, 0);
  EXPECT_LT(max_error / max_entry, 1e-6) << "max error " << max_error << ", max entry " << max_entry;
}

TEST(ContactState, Transitions) {
  StateTolerances tol;
  tol.gap = 1e-12, tol.force = 1e-12;
  NodeQuantities q;
  q.gn = -1e-3, q.gt_norm = 1e-5;
  EXPECT_EQ(next_state(NodeState::Inactive, q, 0.3, tol), NodeState::Stick);     // B
  q.gt_norm = 1e-2;
  EXPECT_EQ(next_state(NodeState::Inactive, q, 0.3, tol), NodeState::Slip);      // A
  EXPECT_EQ(next_state(NodeState::Inactive, q, 0.0, tol), NodeState::Slip);      // frictionless
  q.gn = 1e-3;
  EXPECT_EQ(next_state(NodeState::Inactive, q, 0.3, tol), NodeState::Inactive);  // open gap
  q = {};
  q.lambda_n = -1e-3;
  EXPECT_EQ(next_state(NodeState::Stick, q, 0.3, tol), NodeState::Inactive);     // C (tension)
  q.lambda_n = 1, q.lambda_t_norm = 0.5;
  EXPECT_EQ(next_state(NodeState::Stick, q, 0.3, tol), NodeState::Slip);         // E
  q.lambda_t_norm = 0.2;
  EXPECT_EQ(next_state(NodeState::Stick, q, 0.3, tol), NodeState::Stick);
  q.lambda_t_norm = 0.3, q.gt_norm = 1e-3, q.gt_dot_lt = 0.3e-3;                  // slip reversed
  EXPECT_EQ(next_state(NodeState::Slip, q, 0.3, tol), NodeState::Stick);         // D
  q.gt_dot_lt = -0.3e-3;
  EXPECT_EQ(next_state(NodeState::Slip, q, 0.3, tol), NodeState::Slip);
}

}  // namespace
}  // namespace stiction::contact
