// The recorded sample of a sweep (`stiction bench --sample`): the path run records only the
// chosen Newton systems, every backend replays them in a process of its own, samples.csv
// gets one row each with the residual of its answer checked, and the report labels its
// figures as the sample's. A sweep never overwrites a finished one, and a resumed sweep
// refuses a binary of another revision unless told otherwise.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "csv_table.hpp"

namespace {

namespace fs = std::filesystem;
using stiction::harness::number;
using stiction::harness::read_csv;
using stiction::test::CliRun;
using stiction::test::read_file;

class SampleSweep : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = stiction::test::make_temporary_directory("stiction-sample");
    ASSERT_FALSE(dir_.empty()) << "cannot create a temporary directory";
  }
  void TearDown() override {
    std::error_code ignored;
    if (!dir_.empty()) fs::remove_all(dir_, ignored);
  }
  fs::path dir_;
};

TEST_F(SampleSweep, SolveRecordsOnlyTheChosenSystems) {
  const CliRun run = CliRun::of({"solve", "contact-patch-2d", "--solver", "lu-mumps", "--out", "out", "--no-vtu",
                                 "--quiet", "--record", "rec", "--record-only", "1:2"},
                                dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::vector<std::string> recorded;
  for (const auto& e : fs::directory_iterator(dir_ / "rec")) recorded.push_back(e.path().filename().string());
  ASSERT_EQ(recorded.size(), 1u);
  EXPECT_EQ(recorded[0], "system-001-02");

  const CliRun bad = CliRun::of({"solve", "contact-patch-2d", "--out", "out2", "--no-vtu", "--quiet", "--record",
                                 "rec2", "--record-only", "1-2"},
                                dir_);
  EXPECT_EQ(bad.exit_code, 2);
  ASSERT_EQ(bad.error_lines().size(), 1u) << bad.err;
  EXPECT_NE(bad.error_lines()[0].find("STEP:ITERATION"), std::string::npos) << bad.err;
}

TEST_F(SampleSweep, EveryBackendSolvesTheRecordedSystemsAndTheReportSaysSo) {
  const CliRun run = CliRun::of({"bench", "--scenes", "contact-patch-2d", "--levels", "0", "--solvers",
                                 "lu-mumps,schur-amg,gamg", "--sample", "1:1,1:2,9:1", "--whole", "lu-mumps:0", "--out",
                                 "sweep"},
                                dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto runs = read_csv((dir_ / "sweep/runs.csv").string());
  ASSERT_EQ(runs.rows.size(), 2u);  // the path run (schur-amg) and the whole lu-mumps run
  EXPECT_EQ(runs.rows[0].at("solver"), "schur-amg");
  EXPECT_EQ(runs.rows[1].at("solver"), "lu-mumps");
  for (const auto& r : runs.rows) EXPECT_FALSE(r.at("revision").empty());

  const auto samples = read_csv((dir_ / "sweep/samples.csv").string());
  ASSERT_EQ(samples.rows.size(), 3u);
  std::map<std::string, std::map<std::string, std::string>> by_solver;
  for (const auto& r : samples.rows) by_solver[r.at("solver")] = r;
  // The scene has one load step of a few Newton iterations: 9:1 does not exist on its path.
  for (const std::string solver : {"lu-mumps", "schur-amg"}) {
    const auto& r = by_solver.at(solver);
    EXPECT_EQ(r.at("status"), "ok") << solver;
    EXPECT_EQ(number(r, "systems"), 2) << solver;
    EXPECT_EQ(number(r, "systems_converged"), 2) << solver;
    EXPECT_NE(r.at("detail").find("2 of the 3 requested systems"), std::string::npos) << r.at("detail");
    EXPECT_GT(number(r, "seconds_per_linear_solve"), 0) << solver;
    EXPECT_GT(number(r, "peak_rss_mb"), 0) << solver;
    EXPECT_GT(number(r, "projected_total_seconds"), 0) << solver;
  }
  // The residual is the harness's own check of each answer: a factorisation to round-off,
  // GMRES to about its tolerance (the scene's 1e-4 here, within the 10x the check allows).
  EXPECT_LT(number(by_solver.at("lu-mumps"), "max_relative_residual"), 1e-10);
  EXPECT_GT(number(by_solver.at("schur-amg"), "max_relative_residual"), 1e-10);
  EXPECT_LT(number(by_solver.at("schur-amg"), "max_relative_residual"), 1e-3);
  EXPECT_EQ(number(by_solver.at("schur-amg"), "krylov_per_solve") > 1, true);
  // gamg cannot precondition a saddle point: it fails on the first system and stops there.
  EXPECT_EQ(by_solver.at("gamg").at("status"), "failed");
  EXPECT_EQ(number(by_solver.at("gamg"), "systems"), 1);

  const std::string report = read_file(dir_ / "sweep/report.md");
  EXPECT_NE(report.find("every backend on the recorded sample"), std::string::npos);
  EXPECT_NE(report.find("Total s is projected"), std::string::npos);
}

TEST_F(SampleSweep, WithoutASampleNoSampleIsWritten) {
  const CliRun run = CliRun::of({"bench", "--scenes", "contact-patch-2d", "--levels", "0", "--solvers", "lu-mumps",
                                 "--out", "sweep"},
                                dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(fs::exists(dir_ / "sweep/runs.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "sweep/samples.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "sweep/records"));
  EXPECT_EQ(read_file(dir_ / "sweep/report.md").find("recorded sample"), std::string::npos);
}

TEST_F(SampleSweep, AFinishedSweepIsNeverOverwrittenAndAResumeChecksTheRevision) {
  const std::vector<std::string> sweep{"bench", "--scenes", "contact-patch-2d", "--levels", "0", "--solvers",
                                       "lu-mumps", "--out", "sweep"};
  ASSERT_EQ(CliRun::of(sweep, dir_).exit_code, 0);
  const std::string before = read_file(dir_ / "sweep/runs.csv");
  const CliRun again = CliRun::of(sweep, dir_);
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("--resume"), std::string::npos) << again.err;
  EXPECT_EQ(read_file(dir_ / "sweep/runs.csv"), before);

  // The sweep as if a binary of another revision had started it.
  std::string text = before;
  const std::string key = "# git revision: ";
  const size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.insert(at + key.size(), "0000000other ");
  std::ofstream(dir_ / "sweep/runs.csv") << text;
  std::vector<std::string> resumed = sweep;
  resumed.push_back("--resume");
  const CliRun refused = CliRun::of(resumed, dir_);
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--allow-other-revision"), std::string::npos) << refused.err;
  resumed.push_back("--allow-other-revision");
  const CliRun allowed = CliRun::of(resumed, dir_);
  EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_NE(read_file(dir_ / "sweep/runs.csv").find("# resumed:"), std::string::npos);
}

TEST_F(SampleSweep, BadSampleOptionsAreRefusedBeforeAnyRun) {
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--sample", "2"}, {"--sample", "1:1", "--whole", "lu-mumps"},
        {"--sample", "1:1", "--whole", "nosuch:0"}, {"--sample", "1:1", "--whole", "lu-mumps:3"},
        {"--whole", "lu-mumps:0"}, {"--sample", "1:1", "--path-solver", "nosuch"}}) {
    std::vector<std::string> args{"bench", "--scenes", "contact-patch-2d", "--levels", "0", "--solvers", "lu-mumps",
                                  "--out", "bad"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun run = CliRun::of(args, dir_);
    EXPECT_EQ(run.exit_code, 2) << extra[0] << " " << extra[1];
    EXPECT_EQ(run.error_lines().size(), 1u) << run.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad/runs.csv")) << extra[0] << " " << extra[1];
  }
}

}  // namespace
