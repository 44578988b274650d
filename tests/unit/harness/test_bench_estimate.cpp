// The time-left estimate of a sweep's progress line (bench_estimate.hpp), against sums
// worked by hand from the finished runs' wall times.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "bench_estimate.hpp"

namespace stiction::harness {
namespace {

TEST(BenchEstimate, NothingFinishedSaysSoInsteadOfZeroMinutes) {
  const std::vector<BenchRun> runs{{"block-strips", "schur-amg", 0}, {"block-strips", "lu-mumps", 0}};
  const FinishedRuns none;
  EXPECT_EQ(estimate_seconds(runs[0], none), 0.0);
  EXPECT_EQ(time_left(runs, 0, 30.0, none), "time left not yet estimable (2 runs to go)");
  EXPECT_EQ(time_left(runs, 1, 0.0, none), "time left not yet estimable (1 run to go)");
}

TEST(BenchEstimate, OneLevelUpGrowsAsTheSameBackendGrewOnAnotherScene) {
  FinishedRuns finished;
  finished.add({"a", "schur-amg", 0}, 10.0);
  finished.add({"a", "schur-amg", 1}, 50.0);  // 5x from level 0 to 1
  finished.add({"b", "schur-amg", 0}, 20.0);
  EXPECT_DOUBLE_EQ(estimate_seconds({"b", "schur-amg", 1}, finished), 100.0);
  // No growth measured for lu-mumps: 15x its level-0 time.
  finished.add({"b", "lu-mumps", 0}, 4.0);
  EXPECT_DOUBLE_EQ(estimate_seconds({"b", "lu-mumps", 1}, finished), 60.0);
  // Another process count is another run: nothing one level down on two processes.
  EXPECT_EQ(estimate_seconds({"b", "schur-amg", 1, 2}, finished), 50.0);  // mean at level 1
}

TEST(BenchEstimate, TimeLeftSubtractsTheCurrentRunsElapsedTimeAndCountsTheUnknown) {
  FinishedRuns finished;
  finished.add({"a", "schur-amg", 0}, 60.0);
  const std::vector<BenchRun> runs{{"a", "schur-amg", 0}, {"a", "schur-amg", 1}, {"a", "gamg", 2}};
  // Run 1 (level 1): 15 x 60 s = 900 s, 300 s of it elapsed; run 2 has no basis.
  EXPECT_EQ(time_left(runs, 1, 300.0, finished), "about 10 min left + 1 run not yet estimable");
  finished.add({"a", "gamg", 1}, 120.0);
  // Run 2 now: 15 x 120 s = 1800 s; the current run past its estimate counts 0, and says so.
  EXPECT_EQ(time_left(runs, 1, 1000.0, finished), "about 30 min left (this run past its estimate of 15 min)");
}

// Under a minute the figures are seconds: a 15 x 2 s = 30 s estimate is not "0 min".
TEST(BenchEstimate, UnderAMinuteInSeconds) {
  FinishedRuns finished;
  finished.add({"a", "schur-amg", 0}, 2.0);
  const std::vector<BenchRun> runs{{"a", "schur-amg", 0}, {"a", "schur-amg", 1}};
  EXPECT_EQ(time_left(runs, 1, 10.0, finished), "about 20 s left");
  EXPECT_EQ(time_left(runs, 1, 45.0, finished), "about 0 s left (this run past its estimate of 30 s)");
}

// Once a load step of the current run has finished, the run's total is its elapsed time over
// the fraction the same backend's run one level down had spent by that step: a run whose
// slow (sliding) steps come last is not taken for one about to end.
TEST(BenchEstimate, TheCurrentRunFollowsTheLoadPathOfItsRunOneLevelDown) {
  FinishedRuns finished;
  finished.add({"a", "lu-mumps", 0}, 40.0, {0.05, 0.1, 0.5, 1.0});
  const std::vector<BenchRun> runs{{"a", "lu-mumps", 0}, {"a", "lu-mumps", 1}};
  // Before a step: 15 x 40 s = 600 s, of which 700 s elapsed would be past the estimate.
  EXPECT_DOUBLE_EQ(estimate_current_seconds(runs[1], 0, 700.0, finished), 600.0);
  // Two of four steps done in 700 s, where level 0 had spent 10%: 7 000 s in all.
  EXPECT_DOUBLE_EQ(estimate_current_seconds(runs[1], 2, 700.0, finished), 7000.0);
  EXPECT_EQ(time_left(runs, 1, 700.0, finished, 2), "about 105 min left");
  // A sweep that stops each run after an hour: 3 600 - 700 s left.
  EXPECT_EQ(time_left(runs, 1, 700.0, finished, 2, 3600.0), "about 48 min left");
  // More steps than the run below had (another load path): the whole-run estimate again.
  EXPECT_DOUBLE_EQ(estimate_current_seconds(runs[1], 5, 700.0, finished), 600.0);
  // A run below without a profile (an older sweep's): the same.
  finished.add({"a", "gamg", 0}, 40.0);
  EXPECT_DOUBLE_EQ(estimate_current_seconds({"a", "gamg", 1}, 2, 700.0, finished), 600.0);
}

TEST(BenchEstimate, LoadStepFractionsComeFromTheRunsStepsCsv) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "bench-estimate";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "steps.csv") << "# a run's header\nstep,time,wall_seconds\n1,1,1.0\n2,2,1.0\n3,3,2.0\n";
  EXPECT_EQ(load_step_fractions((dir / "steps.csv").string()), (std::vector<double>{0.25, 0.5, 1.0}));
  EXPECT_TRUE(load_step_fractions((dir / "missing.csv").string()).empty());
}

}  // namespace
}  // namespace stiction::harness
