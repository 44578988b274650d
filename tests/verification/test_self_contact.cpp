// Self-contact (built-in scene self-contact-2d): the upper arm of a slotted block is pushed
// down by 0.025 per load step near its end, the slot being 0.1 wide. The slot stays open in
// step 1, has closed by step 6, and the closed slot neither interpenetrates nor pulls:
// every slave node's mean gap is >= 0 up to the state machine's gap tolerance, the contact
// nodes carry compressive multipliers, and the contact force pushes the upper arm up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/contact_pair.hpp"
#include "support/solve_scene.hpp"

namespace stiction::test {
namespace {

TEST(SelfContact, SlotClosesWithoutPenetration) {
  const SolvedScene s = solve_builtin("self-contact-2d", 0, "lu-mumps");
  ASSERT_TRUE(s.converged()) << s.steps.back().detail;
  ASSERT_EQ(s.steps.size(), 6u);
  const auto& first = s.steps.front().contact.at(0), last = s.steps.back().contact.at(0);
  EXPECT_EQ(first.stick + first.slip, 0) << "the slot should still be open after step 1";
  EXPECT_GT(last.slip, 2) << "the slot should have closed over several nodes";
  EXPECT_GT(last.force[1], 0) << "the lower arm pushes the upper arm up";

  const auto& pair = dynamic_cast<const contact::ContactPair&>(*s.scene->contacts.at(0));
  const std::vector<double> gaps = pair.mean_normal_gaps(1.0, s.u);
  const double tolerance = 1e-8 * pair.slave().diameter;  // above the state machine's 1e-9
  for (int i = 0; i < pair.slave().n_nodes(); ++i) {
    EXPECT_GE(gaps[i], -tolerance) << "node " << i << " penetrates";
    if (pair.state(i) == contact::NodeState::Inactive) continue;
    EXPECT_NEAR(gaps[i], 0.0, tolerance) << "contact node " << i;
    EXPECT_GT(s.lambda[2 * i + 1], 0.0) << "contact node " << i << " pulls";
  }
}

}  // namespace
}  // namespace stiction::test
