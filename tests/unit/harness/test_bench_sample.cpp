// The recorded sample's row (bench_sample.hpp) from a replay's CSV: averages over the
// converged systems, the harness's residual check, and the projected total, against sums
// worked out by hand.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bench_sample.hpp"
#include "csv_table.hpp"
#include "replay_command.hpp"
#include "system_record.hpp"

namespace stiction::harness {
namespace {

namespace fs = std::filesystem;

std::map<std::string, std::string> row_of(const std::string& line) {
  return parse_csv(std::string(kSampleColumns) + "\n" + line).rows.at(0);
}

class SampleRow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / "stiction-sample-row";
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void write_replay(const std::string& rows) {
    std::ofstream(dir_ / "replay.csv") << "# solver: x\n" << kReplayColumns << "\n" << rows;
  }
  fs::path dir_;
  // A path run: 100 s in all, of which 30 s set-up and 50 s solving, over 20 linear solves.
  const std::map<std::string, std::string> path_{{"status", "ok"},        {"wall_seconds", "100"},
                                                 {"setup_seconds", "30"}, {"solve_seconds", "50"},
                                                 {"linear_solves", "20"}};
};

TEST_F(SampleRow, AveragesTheConvergedSystemsAndProjectsTheTotal) {
  write_replay("a,10,1,CONVERGED_RTOL,30,1,1e-5,1.0,2.0,1e-4,5e-5,50,1e-4\n"
               "b,10,1,CONVERGED_RTOL,50,1,1e-5,3.0,4.0,1e-4,9e-4,50,1e-4\n");
  ChildResult child;
  child.exit_code = 0;
  child.peak_rss_mb = 123;
  const auto r = row_of(sample_row("s", 1, "x", dir_.string(), child, path_, 2, "rev"));
  EXPECT_EQ(r.at("status"), "ok");
  EXPECT_DOUBLE_EQ(number(r, "krylov_per_solve"), 40.0);
  EXPECT_DOUBLE_EQ(number(r, "setup_seconds_per_solve"), 2.0);
  EXPECT_DOUBLE_EQ(number(r, "solve_seconds_per_solve"), 3.0);
  EXPECT_DOUBLE_EQ(number(r, "seconds_per_linear_solve"), 5.0);
  EXPECT_DOUBLE_EQ(number(r, "max_relative_residual"), 9e-4);
  EXPECT_DOUBLE_EQ(number(r, "peak_rss_mb"), 123.0);
  // 100 - (30 + 50) + 20 x 5
  EXPECT_DOUBLE_EQ(number(r, "projected_total_seconds"), 120.0);
  EXPECT_DOUBLE_EQ(projected_total_seconds(path_, 4.0), 100.0);  // the path's own speed gives its own total
  EXPECT_EQ(r.at("revision"), "rev");
}

TEST_F(SampleRow, AnAnswerFarFromItsToleranceIsInaccurate) {
  // 2e-3 is 20x the tolerance 1e-4 the system was asked for.
  write_replay("a,10,1,CONVERGED_RTOL,30,1,1e-5,1.0,2.0,1e-4,2e-3,50,1e-4\n");
  ChildResult child;
  child.exit_code = 0;
  const auto r = row_of(sample_row("s", 1, "x", dir_.string(), child, path_, 1, "rev"));
  EXPECT_EQ(r.at("status"), "inaccurate");
  EXPECT_EQ(number(r, "projected_total_seconds"), 0);
}

TEST_F(SampleRow, AFailedSolveOrAKilledReplayIsNamed) {
  write_replay("a,10,0,DIVERGED_ITS,1000,1,1e-1,1.0,2.0,1e-1,1e-1,50,1e-4\n");
  ChildResult child;
  child.exit_code = 0;
  auto r = row_of(sample_row("s", 1, "x", dir_.string(), child, path_, 3, "rev"));
  EXPECT_EQ(r.at("status"), "failed");
  EXPECT_NE(r.at("detail").find("DIVERGED_ITS"), std::string::npos);
  child.hit_time_limit = true;
  child.wall_seconds = 60;
  r = row_of(sample_row("s", 1, "x", dir_.string(), child, path_, 3, "rev"));
  EXPECT_EQ(r.at("status"), "time-limit");
  EXPECT_NE(r.at("detail").find("1 of 3 systems"), std::string::npos) << r.at("detail");
}

TEST(SystemSelection, ReadsStepIterationPairsAndRefusesOtherForms) {
  const auto s = parse_system_selection({"2:2", "6:1"});
  EXPECT_EQ(s.size(), 2u);
  EXPECT_TRUE(s.count({2, 2}));
  EXPECT_TRUE(s.count({6, 1}));
  for (const std::string bad : {"2", "2:", ":2", "0:1", "2:0", "2:2:2", "a:b", "2:2x"})
    EXPECT_THROW(parse_system_selection({bad}), Error) << bad;
}

}  // namespace
}  // namespace stiction::harness
