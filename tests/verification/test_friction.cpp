// Coulomb friction against a rigid plane (built-in scene sliding-block-2d): an elastic block
// is pressed on the plane (step 1), its top pulled sideways a little (step 2: the tangential
// force stays below mu N, nodes stick) and then far (step 3: the block slides, every contact
// node slips and the tangential force is mu N).
#include <gtest/gtest.h>

#include <cmath>

#include "contact/rigid_plane_contact.hpp"
#include "support/solve_scene.hpp"

namespace stiction::test {
namespace {

TEST(Friction, SticksBelowMuNThenSlidesWithMuN) {
  const SolvedScene s = solve_builtin("sliding-block-2d", 0, "lu-mumps");
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
