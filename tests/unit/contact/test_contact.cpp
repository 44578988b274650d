// Contact against a rigid plane: the blocks of (30) are the derivatives of the contact
// residual (finite differences, states frozen), and the state machine's transitions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "contact/rigid_plane_contact.hpp"
#include "contact/surface_contact.hpp"
#include "scene/scene.hpp"
#include "support/solve_scene.hpp"

namespace stiction::contact {
namespace {

const std::string kMaterial = R"(
[[material]]
name = "m"
model = "linear"
E = 2.0
nu = 0.3
)";

const std::string kBlockOnPlane = kMaterial + R"(
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

const std::string kBlockOnBlock = kMaterial + R"(
[[body]]
name = "base"
material = "m"
[body.mesh]
generator = "polygon"
h = 0.4
points = [-0.5, 0.0, 1.5, 0.0, 1.5, 1.0, -0.5, 1.0]
sides = ["bottom", "right", "top", "left"]

[[body]]
name = "block"
material = "m"
[body.mesh]
generator = "polygon"
h = 0.3
points = [0.0, 1.0, 1.0, 1.0, 1.0, 1.6, 0.0, 1.6]
sides = ["bottom", "right", "top", "left"]

[[contact]]
body = "block"
boundary = "bottom"
master = "surface"
master_body = "base"
master_boundary = "top"
friction = 0.4
normal_linearisation = "exact"
)";

// Largest |analytic - central difference| over every entry of the contact blocks and the
// largest analytic entry, at (u, lambda) with the states as set, previous step u0.
std::pair<double, double> jacobian_error(ContactPair& pair, int n_u, const std::vector<double>& u0,
                                         const std::vector<double>& u, const std::vector<double>& lambda) {
  const int n_l = pair.n_multipliers(), n = n_u + n_l;
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
  return {max_error, max_entry};
}

// The contact blocks equal the central differences to 1e-6 relative to the largest entry.
void expect_exact_jacobian(ContactPair& pair, int n_u, const std::vector<double>& u0, const std::vector<double>& u,
                           const std::vector<double>& lambda) {
  const auto [max_error, max_entry] = jacobian_error(pair, n_u, u0, u, lambda);
  EXPECT_GT(max_entry, 0);
  EXPECT_LT(max_error / max_entry, 1e-6) << "max error " << max_error << ", max entry " << max_entry;
}

// Random displacements of the given amplitude; the states cycle inactive / stick / slip
// over the slave nodes and lambda_n = lambda . e_normal is kept positive.
void random_state(ContactPair& pair, int n_u, double amplitude, int normal_axis, std::vector<double>& u0,
                  std::vector<double>& u, std::vector<double>& lambda) {
  const int d = pair.slave().dim;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  u0.assign(n_u, 0.0), u.assign(n_u, 0.0), lambda.assign(pair.n_multipliers(), 0.0);
  for (double& v : u0) v = 0.5 * amplitude * U(rng);
  for (double& v : u) v = amplitude * U(rng);
  for (int i = 0; i < pair.slave().n_nodes(); ++i) {
    pair.set_state(i, static_cast<NodeState>(i % 3));
    for (int c = 0; c < d; ++c) lambda[d * i + c] = U(rng) + (c == normal_axis ? 2.0 : 0.0);
  }
}

// Every entry of the contact blocks against central differences of (r_u, r_c), with a mix
// of inactive, sticking and slipping nodes and a tilted, moving plane.
TEST(RigidPlaneContact, JacobianMatchesFiniteDifferences) {
  auto s = scene::build_scene(kBlockOnPlane, "block-on-plane", ".");
  auto& pair = dynamic_cast<RigidPlaneContact&>(*s->contacts.at(0));
  std::vector<double> u0, u, lambda;
  random_state(pair, s->space->n_dofs(), 0.02, 2, u0, u, lambda);
  expect_exact_jacobian(pair, s->space->n_dofs(), u0, u, lambda);
}

// The same for a deformable master (non-matching P2 meshes, slave narrower than the master
// so that every slave point keeps a projection): the blocks include the variation of the
// nodal normals, of the projection point and of B_ext. The master moves by a random affine
// map (so it stays flat and the segment-wise Gauss rule integrates exactly; on a kinked
// master the analytic blocks are exact up to that quadrature error), the slave randomly.
TEST(SurfaceContact, JacobianMatchesFiniteDifferences) {
  auto s = scene::build_scene(kBlockOnBlock, "block-on-block", ".");
  auto& pair = dynamic_cast<SurfaceContact&>(*s->contacts.at(0));
  const fem::FieldSpace& space = *s->space;
  // n points from the base to the block (+y): lambda_n ~ lambda_y > 0.
  std::vector<double> u0, u, lambda;
  random_state(pair, space.n_dofs(), 0.01, 1, u0, u, lambda);
  // Base nodes (body 0) follow affine maps, at both the previous and the current state.
  std::vector<char> in_block(space.n_nodes(), 0);
  std::vector<int> nodes(space.nodes_per_cell());
  for (int c = 0; c < s->mesh.n_cells(); ++c) {
    if (s->body_of_cell[c] != 1) continue;
    space.cell_nodes(c, nodes.data());
    for (int n : nodes) in_block[n] = 1;
  }
  auto affine = [](double a, double b, double c, double d, double e, double f) {
    return [=](const double* X, double* out) { out[0] = a * X[0] + b * X[1] + e, out[1] = c * X[0] + d * X[1] + f; };
  };
  std::vector<double> base_now, base_before;
  space.interpolate(affine(0.004, -0.003, 0.002, -0.006, 0.003, -0.002), base_now);
  space.interpolate(affine(0.001, 0.002, -0.001, -0.003, -0.002, 0.001), base_before);
  for (int n = 0; n < space.n_nodes(); ++n)
    if (!in_block[n])
      for (int c = 0; c < 2; ++c) u[2 * n + c] = base_now[2 * n + c], u0[2 * n + c] = base_before[2 * n + c];
  expect_exact_jacobian(pair, space.n_dofs(), u0, u, lambda);
}

// A curved master without kinks: the base's top is a single P2 facet with a random
// (curved) displacement, so the closest-point terms with the master's curvature are exact.
TEST(SurfaceContact, JacobianMatchesFiniteDifferencesOnACurvedMaster) {
  auto s = scene::build_scene(test::replaced(kBlockOnBlock, "h = 0.4", "h = 4.0"), "block-on-curved-block", ".");
  auto& pair = dynamic_cast<SurfaceContact&>(*s->contacts.at(0));
  std::vector<double> u0, u, lambda;
  random_state(pair, s->space->n_dofs(), 0.01, 1, u0, u, lambda);
  expect_exact_jacobian(pair, s->space->n_dofs(), u0, u, lambda);
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
