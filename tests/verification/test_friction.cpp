// Coulomb friction against a rigid plane (plane strain): an elastic block is pressed on the
// plane (step 1), its top pulled sideways a little (step 2: the tangential force stays
// below mu N, nodes stick) and then far (step 3: the block slides, every contact node
// slips and the tangential force is mu N).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/rigid_plane_contact.hpp"
#include "support/solve_scene.hpp"

namespace stiction::test {
namespace {

const char* kSlidingBlock = R"(
[scene]
name = "sliding-block-2d"

[[material]]
name = "rubber"
model = "linear"
E = 1.0
nu = 0.3

[[body]]
name = "block"
material = "rubber"
mesh = { generator = "structured-box", size = [1.0, 0.4], cells = [10, 4] }

[[dirichlet]]
boundary = "ymax"
components = ["y"]
value = [-0.01]
schedule = [1.0, 1.0, 1.0]

[[dirichlet]]
boundary = "ymax"
components = ["x"]
value = [0.05]
schedule = [0.0, 0.004, 1.0]

[[contact]]
name = "ground"
boundary = "ymin"
master = "plane"
point = [0.0, 0.0]
normal = [0.0, 1.0]
friction = 0.3

[load]
steps = 3
)";

TEST(Friction, SticksBelowMuNThenSlidesWithMuN) {
  const SolvedScene s = solve_scene_text(kSlidingBlock, 0, "lu-mumps");
  ASSERT_TRUE(s.converged()) << s.steps.back().detail;
  ASSERT_EQ(s.steps.size(), 3u);
  const double mu = 0.3;
  const auto& press = s.steps[0].contact.at(0);
  EXPECT_GT(press.force[1], 0);
  EXPECT_LT(std::abs(press.force[0]), 1e-2 * mu * press.force[1]);  // pressing: hardly any shear

  const auto& stick = s.steps[1].contact.at(0);
  EXPECT_GT(stick.stick, 0) << "a small pull leaves nodes sticking";
  EXPECT_LT(std::abs(stick.force[0]), mu * stick.force[1]);
  EXPECT_GT(std::abs(stick.force[0]), 0);

  const auto& slide = s.steps[2].contact.at(0);
  EXPECT_EQ(slide.stick, 0) << "a large pull makes the whole contact slide";
  EXPECT_GT(slide.slip, 0);
  EXPECT_NEAR(std::abs(slide.force[0]) / (mu * slide.force[1]), 1.0, 1e-6);
  // Friction opposes the block's slip (+x): the ground pulls it back.
  EXPECT_LT(slide.force[0], 0);
  for (const auto& step : s.steps) EXPECT_LT(step.iterations.size(), 10u) << "load step " << step.step;
}

}  // namespace
}  // namespace stiction::test
