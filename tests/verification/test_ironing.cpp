// The shallow ironing (built-in scenes ironing-2d and ironing-2d-frictionless, level 0):
// the force on the indenter at the end of the pressing phase against the published band,
// the contact-state gate of the Newton driver that makes its first contact converge, and
// the Krylov tolerance that keeps schur-amg on the exact Newton path while it slides.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "builtin_scenes.hpp"
#include "checkpoint.hpp"
#include "registry.hpp"
#include "support/solve_scene.hpp"

namespace stiction::test {
namespace {

struct IroningRun {
  std::unique_ptr<scene::Scene> scene;
  std::vector<nonlinear::StepResult> steps;
};

IroningRun run_until(const std::string& text, double until, const std::function<void(scene::Scene&)>& adjust = {}) {
  IroningRun r;
  r.scene = scene::build_scene(text, "ironing", ".", 0);
  if (adjust) adjust(*r.scene);
  auto solver = solvers::create_solver("lu-mumps", PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, r.scene->problem, r.scene->newton, *solver);
  r.steps = newton.run({}, 1, r.scene->problem.step_reaching(until));
  return r;
}

// ironing-2d with the defaults through the pressing and the first 20 sliding steps (t = 1.1),
// solved once for the tests that read it.
const IroningRun& frictional_run() {
  static const IroningRun run = run_until(harness::builtin_scenes().at("ironing-2d"), 1.1);
  return run;
}

// Published band for the force on the indenter at t = 1, per unit thickness, with friction
// 0.3 (the summary of Yang, Laursen & Meng 2005 and the later ironing benchmarks):
// vertical 268-332, horizontal 55-71. The force is the reaction on the indenter's top (F2),
// which the multiplier's integral (F3) must match.
TEST(Ironing, ForceOnTheIndenterAfterPressingLiesInThePublishedBand) {
  const IroningRun& r = frictional_run();
  const auto pressed = std::find_if(r.steps.begin(), r.steps.end(), [](const auto& s) { return s.step == 10 && s.completes_step; });
  ASSERT_NE(pressed, r.steps.end());
  ASSERT_DOUBLE_EQ(pressed->time, 1.0);
  ASSERT_TRUE(pressed->converged()) << pressed->detail;
  const auto reaction = pressed->reactions.at("indenter/top");
  const auto contact = pressed->contact.at(0).force;  // on the slave (the indenter)
  EXPECT_GE(-reaction[1], 268.0);
  EXPECT_LE(-reaction[1], 332.0);
  EXPECT_GE(std::abs(reaction[0]), 55.0);
  EXPECT_LE(std::abs(reaction[0]), 71.0);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(contact[k], -reaction[k], 1e-6 * std::abs(reaction[1])) << k;
}

// The first 20 sliding steps with friction (t = 1 to 1.1): the slab piles up against the
// indenter's front side, which is part of the slave surface. With the arc alone as slave
// the slab's top folded over the arc's front end at t = 1.063 and every cut-back of that
// step stalled at a residual of 0.5 (reference 143). Here every step converges at its
// first try, and the force ratio has reached the sliding regime: |F_x| / F_y at least mu
// (Coulomb on a curved, ploughing indenter adds to mu) and below mu + 0.1.
TEST(Ironing, SlidingWithFrictionPassesTheFrontOfTheArcWithoutCutBacks) {
  const IroningRun& r = frictional_run();
  ASSERT_TRUE(r.steps.back().converged()) << r.steps.back().detail;
  ASSERT_DOUBLE_EQ(r.steps.back().time, 1.1);
  for (const auto& step : r.steps) EXPECT_FALSE(step.retried) << "step " << step.step << " at t = " << step.time;
  EXPECT_EQ(r.steps.size(), 30u);
  const auto reaction = r.steps.back().reactions.at("indenter/top");
  const double ratio = std::abs(reaction[0]) / -reaction[1];
  EXPECT_GE(ratio, 0.3);
  EXPECT_LE(ratio, 0.4);
}

// The first sliding steps of the frictional ironing: with the states updated after every
// linear solve (the paper's rule, state_update_tolerance = 0) nodes at the edge of the
// contact zone flip in turn and load step 19 (t = 1.045) stops with an active-set cycle;
// with the default gate every step to t = 1.05 converges. Cut-backs are off to see the raw
// method. (With the indenter's sharp corners the same cycle appeared at first contact of
// the frictionless variant, t = 0.3; with its fillets that one converges either way.)
TEST(Ironing, StateUpdateGateRemovesTheSlidingContactCycle) {
  const std::string text = harness::builtin_scenes().at("ironing-2d");
  const IroningRun gated = run_until(text, 1.05, [](scene::Scene& s) { s.newton.max_cuts = 0; });
  ASSERT_EQ(gated.steps.size(), 20u);
  for (const auto& step : gated.steps) EXPECT_TRUE(step.converged()) << step.step << ": " << step.detail;
  EXPECT_GE(gated.steps.back().contact.at(0).slip, 4) << "the indenter slides over several nodes";

  const IroningRun every_solve = run_until(text, 1.05, [](scene::Scene& s) {
    s.newton.max_cuts = 0;
    s.newton.active_set.update_tolerance = 0;
    s.newton.active_set.cycle_remedies = 0;
  });
  EXPECT_FALSE(every_solve.steps.back().converged());
  EXPECT_EQ(every_solve.steps.back().reason, nonlinear::NewtonReason::DivergedActiveSetCycle);
}

// One load step of ironing-2d at level 0 with schur-amg, restarted from the state after load
// step 145 (t = 1.675) that tests/data/ironing-2d-L0-t1.675-checkpoint.bin holds
// (scripts/make-ironing-checkpoint.sh), at the scene's Krylov tolerance or at the given one
// (0: the backend's 1e-4).
nonlinear::StepResult step_146_of_schur_amg(std::optional<double> krylov_rtol = {}) {
  const auto scene = scene::build_scene(harness::builtin_scenes().at("ironing-2d"), "ironing", ".", 0);
  if (krylov_rtol) scene->newton.krylov_rtol = *krylov_rtol;
  else EXPECT_DOUBLE_EQ(scene->newton.krylov_rtol, 1e-6);
  scene->newton.max_cuts = 0;
  const harness::Checkpoint start =
      harness::read_checkpoint(std::string(STICTION_TEST_DATA) + "/ironing-2d-L0-t1.675-checkpoint.bin");
  auto solver = solvers::create_solver("schur-amg", PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, scene->problem, scene->newton, *solver);
  newton.restore(start.state);
  EXPECT_EQ(start.state.step, 145);
  const auto steps = newton.run({}, 146, 146);
  EXPECT_EQ(steps.size(), 1u);
  return steps.back();
}

// |F_master + F_slave| / |F_slave|: the traction integrated over the slab's contact surface
// against the multiplier's integral over the indenter's (F5 against F3, which agree at a
// well-resolved solution).
double force_mismatch(const nonlinear::StepResult& r) {
  const auto slave = r.contact.at(0).force, master = r.surface_forces.at("ironing/master");
  return std::hypot(master[0] + slave[0], master[1] + slave[1]) / std::hypot(slave[0], slave[1]);
}

// At t = 1.68 the frictional sliding meets a nearly singular tangent. lu-mumps's Newton path
// keeps 28 slipping and 30 free slave nodes and converges in 7 iterations with the slab's
// surface traction within 0.3% of the multiplier's force. schur-amg at the backends' Krylov
// tolerance 1e-4 leaves that path at the second iteration (residual 9.9 where lu-mumps has
// 4.8) and, after 18 iterations, converges to another solution: one slave node on the front
// fillet lifted off (gap 7e-4) inside the slip zone, the slab's traction 29% off the
// multiplier's, and a slab-top cell under it crushed (smallest det F 0.0047, where lu-mumps's
// path keeps 0.69), so Newton now rejects that increment (newton.min_det_f_ratio); before,
// every cut of the next step converged into a folded slab cell. The scene's Krylov
// tolerance 1e-6 keeps schur-amg on lu-mumps's path.
TEST(Ironing, TightKrylovToleranceKeepsTheExactPathWhereSlidingBranches) {
  const auto tight = step_146_of_schur_amg();
  ASSERT_TRUE(tight.converged()) << tight.detail;
  EXPECT_DOUBLE_EQ(tight.time, 1.68);
  EXPECT_EQ(tight.contact.at(0).slip, 28);
  EXPECT_EQ(tight.contact.at(0).inactive, 30);
  EXPECT_LT(force_mismatch(tight), 0.01);
  EXPECT_LE(tight.iterations.size(), 8u);
  for (const auto& it : tight.iterations)
    EXPECT_LE(it.linear.final_residual, 1e-6 * it.linear.initial_residual) << "the scene's tolerance applies";

  EXPECT_GT(tight.min_det_f, 0.5);

  const auto loose = step_146_of_schur_amg(0);
  EXPECT_EQ(loose.reason, nonlinear::NewtonReason::DivergedInvertedElement);
  EXPECT_NE(loose.detail.find("the smallest det F fell from"), std::string::npos)
      << "the other solution of the increment, with a crushed cell: " << loose.detail;
}

}  // namespace
}  // namespace stiction::test
