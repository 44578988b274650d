// A run's metrics record (run_metrics.hpp) keeps the linear solves of the load step under
// way, so that a run stopped inside a long step (a sweep's time limit) still says what its
// solves cost; a restart from the checkpoint drops them, since it solves that step again.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include <petscsys.h>

#include "run_metrics.hpp"
#include "scene/scene.hpp"
#include "support/solve_scene.hpp"

namespace stiction::harness {
namespace {

namespace fs = std::filesystem;

// The bar in two load steps.
std::unique_ptr<scene::Scene> two_step_bar() {
  return scene::build_scene(std::string(test::minimal_bar_scene()) + "\n[load]\nsteps = 2\n", "bar.toml", ".");
}

nonlinear::NewtonIteration iteration(int krylov, double solve_seconds) {
  nonlinear::NewtonIteration it;
  it.linear.converged = true;
  it.linear.reason = "CONVERGED_RTOL";
  it.linear.iterations = krylov;
  it.linear.solve_seconds = solve_seconds;
  return it;
}

toml::table read(const fs::path& p) { return toml::parse_file(p.string()); }

// A record of the two-step bar in a directory of its own, rewritten inside a load step when
// its last write is `interval` old.
class RunRecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  RunRecorder recorder(std::chrono::duration<double> interval) const {
    return RunRecorder(path_.string(), *scene_, RunSummary{"schur-amg", ""}, PETSC_COMM_WORLD, std::nullopt,
                       std::chrono::steady_clock::now(), interval);
  }
  const fs::path dir_ = fs::temp_directory_path() /
                        ("stiction-run-recorder-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  const fs::path path_ = dir_ / "metrics.toml";
  const std::unique_ptr<scene::Scene> scene_ = two_step_bar();
};

TEST_F(RunRecorderTest, KeepsTheSolvesOfTheLoadStepUnderWay) {
  RunRecorder record = recorder(std::chrono::seconds(0));

  // Two Newton iterations of load step 1, which has not ended: each is written at once.
  record.add_iteration(1, 0.5, iteration(40, 2.0));
  record.add_iteration(1, 0.5, iteration(60, 3.0));
  toml::table m = read(path_);
  EXPECT_EQ(m["run"]["reason"].value<std::string>(), "INCOMPLETE");
  EXPECT_EQ(m["run"]["linear_solves"].value<int64_t>(), 2);
  EXPECT_EQ(m["run"]["krylov_iterations"].value<int64_t>(), 100);
  EXPECT_EQ(m["run"]["newton_iterations"].value<int64_t>(), 2);
  EXPECT_EQ(m["run"]["load_steps_completed"].value<int64_t>(), 0);
  ASSERT_EQ(m["step"].as_array()->size(), 1u);
  EXPECT_EQ(m["step"][0]["reason"].value<std::string>(), "IN_PROGRESS");
  EXPECT_DOUBLE_EQ(seconds_per_converged_solve(m["linear_solve"].as_array()), 2.5);

  // The step ends with those two iterations: they are its, not counted twice.
  nonlinear::StepResult step1;
  step1.step = 1;
  step1.time = 0.5;
  step1.reason = nonlinear::NewtonReason::ConvergedRelative;
  step1.completes_step = true;
  step1.iterations = {iteration(40, 2.0), iteration(60, 3.0)};
  record.add(step1);
  m = read(path_);
  EXPECT_EQ(m["run"]["linear_solves"].value<int64_t>(), 2);
  EXPECT_EQ(m["run"]["load_steps_completed"].value<int64_t>(), 1);
  ASSERT_EQ(m["step"].as_array()->size(), 1u);
  EXPECT_NE(m["step"][0]["reason"].value<std::string>(), "IN_PROGRESS");

  // One iteration into step 2: three solves on record; a restart from the checkpoint of
  // step 1 keeps the two of step 1 only.
  record.add_iteration(2, 1.0, iteration(80, 4.0));
  m = read(path_);
  EXPECT_EQ(m["run"]["linear_solves"].value<int64_t>(), 3);
  EXPECT_EQ(m["step"][1]["reason"].value<std::string>(), "IN_PROGRESS");
  const auto earlier = read_earlier_segments(path_.string(), scene_->name, scene_->level, "schur-amg", 1);
  ASSERT_TRUE(earlier);
  EXPECT_EQ(earlier->linear_solves.size(), 2u);
  EXPECT_EQ(earlier->steps.size(), 1u);
}

// Inside a load step the record is rewritten only when the last write is old enough: a run
// of many short iterations does not rewrite its growing record at every one.
TEST_F(RunRecorderTest, WritesTheStepUnderWayAtMostOncePerInterval) {
  RunRecorder record = recorder(std::chrono::hours(1));
  record.add_iteration(1, 0.5, iteration(40, 2.0));
  EXPECT_FALSE(fs::exists(path_)) << "written before its interval";
}

}  // namespace
}  // namespace stiction::harness
