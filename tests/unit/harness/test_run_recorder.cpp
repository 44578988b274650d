// A run's metrics record (run_metrics.hpp) keeps the linear solves of the load step under
// way, so that a run stopped inside a long step (a sweep's time limit) still says what its
// solves cost; a restart from the checkpoint drops them, since it solves that step again.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include <petscsys.h>

#include "run_metrics.hpp"
#include "scene/scene.hpp"

namespace stiction::harness {
namespace {

namespace fs = std::filesystem;

const char* kBar = R"(
[[material]]
name = "steel"
model = "linear"
E = 200.0
nu = 0.3

[[body]]
name = "bar"
material = "steel"
mesh = { generator = "structured-box", size = [4.0, 1.0], cells = [4, 1] }

[[dirichlet]]
boundary = "xmin"
components = ["x", "y"]
value = [0.0, 0.0]

[load]
steps = 2
)";

nonlinear::NewtonIteration iteration(int krylov, double solve_seconds) {
  nonlinear::NewtonIteration it;
  it.linear.converged = true;
  it.linear.reason = "CONVERGED_RTOL";
  it.linear.iterations = krylov;
  it.linear.solve_seconds = solve_seconds;
  return it;
}

toml::table read(const fs::path& p) { return toml::parse_file(p.string()); }

TEST(RunRecorder, KeepsTheSolvesOfTheLoadStepUnderWay) {
  const fs::path dir = fs::temp_directory_path() / "stiction-run-recorder-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "metrics.toml";
  const auto scene = scene::build_scene(kBar, "bar.toml", ".");
  RunRecorder record(path.string(), *scene, RunSummary{"schur-amg", ""}, PETSC_COMM_WORLD, std::nullopt,
                     std::chrono::steady_clock::now(), std::chrono::seconds(0));

  // Two Newton iterations of load step 1, which has not ended: each is written at once.
  record.add_iteration(1, 0.5, iteration(40, 2.0));
  record.add_iteration(1, 0.5, iteration(60, 3.0));
  toml::table m = read(path);
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
  m = read(path);
  EXPECT_EQ(m["run"]["linear_solves"].value<int64_t>(), 2);
  EXPECT_EQ(m["run"]["load_steps_completed"].value<int64_t>(), 1);
  ASSERT_EQ(m["step"].as_array()->size(), 1u);
  EXPECT_NE(m["step"][0]["reason"].value<std::string>(), "IN_PROGRESS");

  // One iteration into step 2: three solves on record; a restart from the checkpoint of
  // step 1 keeps the two of step 1 only.
  record.add_iteration(2, 1.0, iteration(80, 4.0));
  m = read(path);
  EXPECT_EQ(m["run"]["linear_solves"].value<int64_t>(), 3);
  EXPECT_EQ(m["step"][1]["reason"].value<std::string>(), "IN_PROGRESS");
  const auto earlier = read_earlier_segments(path.string(), scene->name, scene->level, "schur-amg", 1);
  ASSERT_TRUE(earlier);
  EXPECT_EQ(earlier->linear_solves.size(), 2u);
  EXPECT_EQ(earlier->steps.size(), 1u);
  fs::remove_all(dir);
}

// Inside a load step the record is rewritten only when the last write is old enough: a run
// of many short iterations does not rewrite its growing record at every one.
TEST(RunRecorder, WritesTheStepUnderWayAtMostOncePerInterval) {
  const fs::path dir = fs::temp_directory_path() / "stiction-run-recorder-interval-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path path = dir / "metrics.toml";
  const auto scene = scene::build_scene(kBar, "bar.toml", ".");
  RunRecorder record(path.string(), *scene, RunSummary{"schur-amg", ""}, PETSC_COMM_WORLD, std::nullopt,
                     std::chrono::steady_clock::now(), std::chrono::hours(1));
  record.add_iteration(1, 0.5, iteration(40, 2.0));
  EXPECT_FALSE(fs::exists(path)) << "written before its interval";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stiction::harness
