// CI guard on iteration counts: the level-0 short version (--quick) of every built-in scene
// with every backend the baseline holds for it, run through `stiction bench` (one CTest
// test per scene, so the sweep spreads over the cores and each scene has its own time-out),
// against tests/regression/iterations.csv. A count may move by at most max(2, 10%) either
// way: a rise is a regression, a fall a change the baseline must record (both need a
// review); see README.md next to this file for what it leaves out and how to update it.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <utility>

#include "builtin_scenes.hpp"
#include "csv_table.hpp"
#include "registry.hpp"
#include "support/test_names.hpp"

namespace stiction {
namespace {

namespace fs = std::filesystem;
using Row = std::map<std::string, std::string>;

// The (scene, backend) pairs left out on purpose, each with its reason.
bool outside_the_baseline(const std::string& scene, const std::string& backend) {
  static const auto pairs = [] {
    std::set<std::pair<std::string, std::string>> out;
    for (const auto& row : harness::read_csv(STICTION_OUTSIDE_BASELINE).rows) out.insert({row.at("scene"), row.at("solver")});
    return out;
  }();
  return pairs.count({"*", backend}) || pairs.count({scene, backend});
}

// scene -> backend -> baseline row
const std::map<std::string, std::map<std::string, Row>>& baseline() {
  static const auto rows = [] {
    std::map<std::string, std::map<std::string, Row>> by_scene;
    for (const auto& row : harness::read_csv(STICTION_BASELINE).rows) by_scene[row.at("scene")][row.at("solver")] = row;
    return by_scene;
  }();
  return rows;
}

std::vector<std::string> baseline_scenes() {
  std::vector<std::string> names;
  for (const auto& [scene, rows] : baseline()) names.push_back(scene);
  return names;
}

bool within_allowance(double measured, double baseline) {
  return std::abs(measured - baseline) <= std::max(2.0, 0.1 * baseline);
}

// Runs `stiction bench` on one scene at level 0 (--quick) with the given backends.
harness::CsvTable run_level0_sweep(const std::string& scene, const std::string& solvers) {
  const fs::path out = fs::path(::testing::TempDir()) / ("iteration-baseline-" + scene);
  fs::remove_all(out);
  const std::string cmd = std::string("OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 '") + STICTION_BINARY +
                          "' bench --scenes " + scene + " --solvers " + solvers + " --levels 0 --quick --out '" +
                          out.string() + "' 2> '" + (out.string() + ".log") + "'";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "bench failed; see " << out.string() << ".log";
  return harness::read_csv((out / "runs.csv").string());
}

class IterationBaseline : public ::testing::TestWithParam<std::string> {};

TEST_P(IterationBaseline, Level0DoesNotRegress) {
  const std::string& scene = GetParam();
  const auto& expected = baseline().at(scene);
  std::string solvers;
  for (const auto& [solver, row] : expected) solvers += (solvers.empty() ? "" : ",") + solver;
  const auto runs = run_level0_sweep(scene, solvers);
  ASSERT_EQ(runs.rows.size(), expected.size()) << "one row per backend of the baseline";
  for (const auto& run : runs.rows) {
    const std::string& solver = run.at("solver");
    SCOPED_TRACE(scene + "/" + solver);
    ASSERT_TRUE(expected.count(solver));
    const Row& base = expected.at(solver);
    ASSERT_EQ(run.at("status"), base.at("status")) << run.at("detail");
    if (run.at("status") != "ok") continue;  // a stable, recorded failure: no counts to compare
    for (const char* what : {"newton_iterations", "krylov_iterations"}) {
      const double measured = std::stod(run.at(what)), recorded = std::stod(base.at(what));
      EXPECT_TRUE(within_allowance(measured, recorded))
          << what << ": " << measured << " vs baseline " << recorded
          << (measured < recorded ? " (fewer: record it with scripts/update-iteration-baseline.sh)" : "");
    }
  }
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) { return test::identifier(info.param); }

INSTANTIATE_TEST_SUITE_P(Scenes, IterationBaseline, ::testing::ValuesIn(baseline_scenes()), test_name);

// The per-scene tests run what the baseline holds; this one makes sure it holds everything:
// every built-in scene with every available backend but the pairs it leaves out on purpose
// (outside-baseline.csv).
TEST(IterationBaselineCoverage, EveryBuiltInSceneWithEveryBackend) {
  ASSERT_FALSE(baseline().empty()) << STICTION_BASELINE;
  for (const auto& [scene, toml] : harness::builtin_scenes()) {
    SCOPED_TRACE(scene);
    ASSERT_TRUE(baseline().count(scene)) << "no baseline rows: add them with scripts/update-iteration-baseline.sh";
    const auto& rows = baseline().at(scene);
    for (const auto& backend : solvers::backends()) {
      if (!backend.unavailable_reason().empty()) continue;
      EXPECT_EQ(rows.count(backend.name), outside_the_baseline(scene, backend.name) ? 0u : 1u) << backend.name;
    }
  }
  for (const auto& [scene, rows] : baseline()) EXPECT_TRUE(harness::builtin_scenes().count(scene)) << scene;
}

}  // namespace
}  // namespace stiction
