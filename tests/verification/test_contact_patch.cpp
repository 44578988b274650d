// Contact patch test (built-in scene contact-patch-2d): two blocks with non-matching meshes
// and different stiffnesses, between rollers, pressed together frictionlessly, carry a
// uniform uniaxial strain; the discrete solution is exact when the contact integrals are
// (mortar-style segments), so every slave node must carry the pressure
//   p = delta / (H1 / M1 + H2 / M2),   M = E (1 - nu) / ((1 + nu) (1 - 2 nu))
// with a normal multiplier and no tangential one, to round-off (asserted to 1e-8 relative).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact/contact_pair.hpp"
#include "support/solve_scene.hpp"

namespace stiction::test {
namespace {

TEST(ContactPatch, NonMatchingMeshesCarryAUniformPressure) {
  const SolvedScene s = solve_builtin("contact-patch-2d", 0, "lu-mumps");
  ASSERT_TRUE(s.converged()) << s.steps.back().detail;
  const auto& pair = dynamic_cast<const contact::ContactPair&>(*s.scene->contacts.at(0));
  const double delta = 0.01, nu = 0.3, E_base = 1.0, E_block = 3.0;
  auto M = [nu](double E) { return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)); };
  const double p = delta / (1.0 / M(E_base) + 1.0 / M(E_block));
  ASSERT_GT(pair.slave().n_nodes(), 5);
  double worst_normal = 0, worst_tangential = 0;
  for (int i = 0; i < pair.slave().n_nodes(); ++i) {
    EXPECT_EQ(pair.state(i), contact::NodeState::Slip) << "node " << i;  // frictionless contact
    worst_normal = std::max(worst_normal, std::abs(s.lambda[2 * i + 1] / p - 1));
    worst_tangential = std::max(worst_tangential, std::abs(s.lambda[2 * i] / p));
  }
  std::printf("%d slave nodes: max |lambda_n / p - 1| = %.2e, max |lambda_t / p| = %.2e\n", pair.slave().n_nodes(),
              worst_normal, worst_tangential);
  EXPECT_LT(worst_normal, 1e-8);
  EXPECT_LT(worst_tangential, 1e-8);
  // The paper's five measures of the force through the interface (width 1) agree:
  // F1 traction integral and F2 nodal reactions on the block's top (pressed down: -p),
  // F3 the multiplier integral, F4 the traction integral on the slave, F5 minus that on the
  // master (all +p on the block).
  const auto& step = s.steps.back();
  const double F1 = step.surface_forces.at("block/top")[1], F2 = step.reactions.at("block/top")[1];
  const double F3 = step.contact.at(0).force[1], F4 = step.surface_forces.at("interface/slave")[1];
  const double F5 = -step.surface_forces.at("interface/master")[1];
  std::printf("F1 %.12e F2 %.12e F3 %.12e F4 %.12e F5 %.12e (p %.12e)\n", F1, F2, F3, F4, F5, p);
  EXPECT_NEAR(F1, -p, 1e-8 * p);
  EXPECT_NEAR(F2, -p, 1e-8 * p);
  EXPECT_NEAR(F3, p, 1e-8 * p);
  EXPECT_NEAR(F4, p, 1e-8 * p);
  EXPECT_NEAR(F5, p, 1e-8 * p);
}

}  // namespace
}  // namespace stiction::test
