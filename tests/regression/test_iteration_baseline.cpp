// CI guard on iteration counts: the level-0 sweep of every built-in scene (its short version,
// --quick) and backend,
// run through `stiction bench`, against tests/regression/iterations.csv. A count may rise
// by at most max(2, 10%); see README.md next to this file for updating the baseline.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "csv_table.hpp"

namespace stiction {
namespace {

namespace fs = std::filesystem;

bool within_allowance(double measured, double baseline) {
  return measured <= baseline + std::max(2.0, 0.1 * baseline);
}

TEST(IterationBaseline, Level0SweepDoesNotRegress) {
  const fs::path out = fs::path(::testing::TempDir()) / "iteration-baseline";
  fs::remove_all(out);
  const std::string cmd = std::string("OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 '") + STICTION_BINARY +
                          "' bench --levels 0 --quick --out '" + out.string() + "' 2> '" + (out.string() + ".log") + "'";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "bench failed; see " << out.string() << ".log";

  const auto baseline = harness::read_csv(STICTION_BASELINE);
  const auto runs = harness::read_csv((out / "runs.csv").string());
  ASSERT_FALSE(baseline.rows.empty());
  ASSERT_FALSE(runs.rows.empty());
  std::map<std::string, std::map<std::string, std::string>> base;
  for (const auto& row : baseline.rows) base[row.at("scene") + "/" + row.at("solver")] = row;
  for (const auto& run : runs.rows) {
    const std::string key = run.at("scene") + "/" + run.at("solver");
    SCOPED_TRACE(key);
    ASSERT_TRUE(base.count(key)) << "no baseline row: add it with scripts/update-iteration-baseline.sh";
    ASSERT_EQ(run.at("status"), base[key].at("status")) << run.at("detail");
    if (run.at("status") != "ok") continue;  // a stable, recorded failure: no counts to compare
    for (const char* what : {"newton_iterations", "krylov_iterations"}) {
      const double measured = std::stod(run.at(what)), expected = std::stod(base[key].at(what));
      EXPECT_TRUE(within_allowance(measured, expected)) << what << ": " << measured << " vs baseline " << expected;
      if (measured < expected - std::max(2.0, 0.1 * expected))
        std::printf("note: %s %s fell from %.0f to %.0f; consider updating the baseline\n", key.c_str(), what,
                    expected, measured);
    }
  }
}

}  // namespace
}  // namespace stiction
