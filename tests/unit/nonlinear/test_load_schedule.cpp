// Piecewise-linear loads in pseudo-time and the contact-state monitor of the Newton driver.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "nonlinear/active_set_monitor.hpp"
#include "nonlinear/load_schedule.hpp"
#include "nonlinear/problem.hpp"

namespace stiction::nonlinear {
namespace {

TEST(PiecewiseLinear, InterpolatesBetweenRowsAndHoldsBeyondThem) {
  const PiecewiseLinear f({0.0, 1.0, 2.0}, {{0.0, 0.0}, {0.0, -1.0}, {10.0, -1.0}});
  double v[2];
  f(0.5, v);
  EXPECT_DOUBLE_EQ(v[0], 0.0);
  EXPECT_DOUBLE_EQ(v[1], -0.5);
  f(1.25, v);
  EXPECT_DOUBLE_EQ(v[0], 2.5);
  EXPECT_DOUBLE_EQ(v[1], -1.0);
  f(3.0, v);  // after the last row
  EXPECT_DOUBLE_EQ(v[0], 10.0);
  f(-1.0, v);  // before the first
  EXPECT_DOUBLE_EQ(v[1], 0.0);
  f(1.0, v);  // exactly on a row
  EXPECT_DOUBLE_EQ(v[1], -1.0);
}

TEST(PiecewiseLinear, RejectsTimesThatDoNotIncreaseAndRaggedRows) {
  EXPECT_THROW(PiecewiseLinear({0.0, 0.0}, {{1.0}, {2.0}}), Error);
  EXPECT_THROW(PiecewiseLinear({0.0, 1.0}, {{1.0}, {2.0, 3.0}}), Error);
  EXPECT_THROW(PiecewiseLinear({}, {}), Error);
}

TEST(StepTimes, UniformStepsAndTheStepReachingATime) {
  ElasticityProblem p;
  p.step_times = uniform_step_times(4);
  ASSERT_EQ(p.n_steps(), 4);
  EXPECT_DOUBLE_EQ(p.step_times[1], 0.25);
  EXPECT_EQ(p.step_reaching(0.3), 2);
  EXPECT_EQ(p.step_reaching(0.5), 2);
  EXPECT_EQ(p.step_reaching(7.0), 4);
}

TEST(ActiveSetMonitor, HoldsStatesUntilTheIterateSolvesThemOrTooLong) {
  ActiveSetSettings s;
  s.update_tolerance = 1e-3;
  s.max_held = 2;
  ActiveSetMonitor m(s);
  EXPECT_FALSE(m.may_update(1e-1, false));
  EXPECT_FALSE(m.may_update(1e-2, false));
  EXPECT_TRUE(m.may_update(1e-2, false)) << "held max_held times: the update is forced";
  EXPECT_TRUE(m.may_update(1e-4, false));
  EXPECT_TRUE(m.may_update(1.0, true)) << "a converged iterate is always checked";
  s.update_tolerance = 0;  // the paper: after every solve
  ActiveSetMonitor every(s);
  EXPECT_TRUE(every.may_update(1e3, false));
}

TEST(ActiveSetMonitor, ARecurringSetIsRemediedThenACycle) {
  ActiveSetSettings s;
  s.cycle_remedies = 1;
  s.remedy_factor = 0.1;
  ActiveSetMonitor m(s);
  const std::vector<char> a{0, 1}, b{1, 1};
  EXPECT_EQ(m.after_update(a, b, 10.0, 9.0), ActiveSetMonitor::Verdict::Continue);
  EXPECT_EQ(m.after_update(b, a, 9.0, 8.0), ActiveSetMonitor::Verdict::Continue) << "the residual fell below 10";
  EXPECT_EQ(m.after_update(a, b, 8.0, 9.5), ActiveSetMonitor::Verdict::Remedied) << "b recurs, 9.5 >= 9";
  EXPECT_DOUBLE_EQ(m.gate(), s.update_tolerance * 0.1);
  EXPECT_EQ(m.after_update(b, a, 9.5, 9.6), ActiveSetMonitor::Verdict::Continue) << "the remedy forgets the past";
  EXPECT_EQ(m.after_update(a, b, 9.6, 9.7), ActiveSetMonitor::Verdict::Cycle) << "b recurs again, no remedy left";
}

}  // namespace
}  // namespace stiction::nonlinear
