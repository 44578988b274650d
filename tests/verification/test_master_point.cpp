// The two 3D master points (ContactSettings::MasterPoint) on a flat deformable master: a
// sphere octant (slave) pressed into the flat bottom of a block (master). On a flat master
// the closest point does not jump between triangles, so Newton converges with either; and
// the two points differ only by the tangential part of the gap vector, whose effect on the
// normal gap is second order in the tilt between the slave normal and the master's, so
// the converged contact force is nearly the same: measured 1.7e-5 relative at level 0
// (lu-mumps, 5 + 6 Newton iterations with either). On two curved bodies the closest point
// fails instead (surface_contact.hpp): hence the crossing by default.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/solve_scene.hpp"

namespace stiction::test {
namespace {

const char* kBallUnderBlock = R"toml(# Root keys first: the supports as an inline array of tables.
dirichlet = [
  { body = "ball", boundary = "base", components = ["y"], value = [0.0] },
  { body = "ball", boundary = "symmetry-x", components = ["x"], value = [0.0] },
  { body = "ball", boundary = "symmetry-z", components = ["z"], value = [0.0] },
  { body = "block", boundary = "ymax", components = ["y"], value = [-0.01] },
  { body = "block", boundary = "xmin", components = ["x"], value = [0.0] },
  { body = "block", boundary = "zmin", components = ["z"], value = [0.0] },
]

[scene]
name = "ball-under-block-3d"
description = "a sphere octant pressed into the flat bottom of a block (the block is the master)"

[[material]]
name = "soft"
model = "linear"
E = 1.0
nu = 0.3

[[body]]
name = "ball"
material = "soft"
[body.mesh]
generator = "sphere-octant"
pole = "top"
radius = 1.0
h = 0.3
contact_size = 0.04
contact_zone = 0.25

[[body]]
name = "block"
material = "soft"
[body.mesh]
generator = "box"
size = [0.4, 0.2, 0.4]
h = 0.05

[[contact]]
name = "interface"
body = "ball"
boundary = "surface"
master = "surface"
master_body = "block"
master_boundary = "ymin"
friction = 0.0

[load]
steps = 2

[output]
vtu = false
)toml";

TEST(MasterPoint3D, ClosestPointAndNormalCrossingAgreeOnAFlatMaster) {
  double force[2];
  const char* rules[2] = {"closest", "normal-crossing"};
  for (int k = 0; k < 2; ++k) {
    const std::string text = replaced(kBallUnderBlock, "friction = 0.0\n",
                                      std::string("friction = 0.0\nmaster_point = \"") + rules[k] + "\"\n");
    const SolvedScene s = solve_scene_text(text, 0, "lu-mumps");
    ASSERT_TRUE(s.converged()) << rules[k] << ": " << s.steps.back().detail;
    for (const auto& step : s.steps) EXPECT_LE(step.iterations.size(), 8u) << rules[k] << ", step " << step.step;
    // The block's top carries the contact force; the ball's base balances it.
    force[k] = -s.steps.back().reactions.at("block/ymax")[1];
    EXPECT_GT(force[k], 0) << rules[k];
    EXPECT_NEAR(s.steps.back().reactions.at("ball/base")[1], force[k], 1e-9 * force[k]) << rules[k];
  }
  std::printf("block reaction: closest point %.10e, normal crossing %.10e (relative difference %.2e)\n", force[0],
              force[1], std::abs(force[0] / force[1] - 1));
  EXPECT_NEAR(force[0], force[1], 1e-4 * force[1]);
}

}  // namespace
}  // namespace stiction::test
