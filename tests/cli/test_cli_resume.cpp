// A long run that is killed (the sweep stopped, the machine went down) keeps the record of
// the load steps it finished; `solve --restart` continues that record, and `bench --resume`
// continues the run from its checkpoint instead of starting it again. Both must end with
// the figures of the uninterrupted run.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "checkpoint.hpp"
#include "cli_run.hpp"
#include "cli_scenes.hpp"
#include "csv_table.hpp"

namespace {

namespace fs = std::filesystem;
using stiction::test::CliRun;
using stiction::test::read_file;

// The cantilever-2d scene over 40 load steps under four times its load: each step takes a
// few milliseconds, so a run can be killed between two of them.
std::string cantilever_40_steps() {
  return stiction::test::SceneVariant{}
      .replace("steps = 4\n", "steps = 40\n")
      .replace("value = [0.0, -1.0]", "value = [0.0, -4.0]")
      .replace("name = \"cantilever-2d\"", "name = \"cantilever-40\"")
      .text;
}

class ResumedRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = stiction::test::make_temporary_directory("stiction-resume");
    ASSERT_FALSE(dir_.empty()) << "cannot create a temporary directory";
    scene_ = dir_ / "cantilever-40.toml";
    std::ofstream(scene_) << cantilever_40_steps();
  }
  void TearDown() override {
    std::error_code ignored;
    if (!dir_.empty()) fs::remove_all(dir_, ignored);
  }

  // Starts `stiction args...` (stdout and stderr to files in dir_) without the MPI variables
  // of this process, and SIGKILLs it as soon as its record (`record`) and the checkpoint
  // beside it hold a completed load step. Returns whether it was killed before it ended by
  // itself.
  bool run_and_kill_after_first_step(const std::vector<std::string>& args, const fs::path& record) const {
    std::vector<std::string> env;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string var = *e;
      if (!stiction::test::is_mpi_variable(var)) env.push_back(var);
    }
    std::vector<std::string> argv{STICTION_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    const pid_t pid = fork();
    if (pid == 0) {
      const int out = open((dir_ / "killed.out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = open((dir_ / "killed.err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(out, 1);
      dup2(err, 2);
      std::vector<char*> a, e;
      for (auto& s : argv) a.push_back(s.data());
      for (auto& s : env) e.push_back(s.data());
      a.push_back(nullptr);
      e.push_back(nullptr);
      execve(a[0], a.data(), e.data());
      _exit(127);
    }
    bool killed = false;
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::seconds(120)) {
      int status = 0;
      if (waitpid(pid, &status, WNOHANG) == pid) return false;  // ended by itself
      // The record is written before the checkpoint: wait for both.
      if (read_file(record).find("INCOMPLETE") != std::string::npos &&
          fs::exists(record.parent_path() / "checkpoint.bin")) {
        kill(pid, SIGKILL);
        killed = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (!killed) kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    return killed && WIFSIGNALED(status);
  }

  fs::path dir_, scene_;
};

toml::table run_table(const fs::path& metrics) { return *toml::parse_file(metrics.string())["run"].as_table(); }

// `solve --metrics` rewrites its record after every completed load step: killed after one,
// the record says INCOMPLETE and holds at least the checkpoint's steps. Restarted with the
// same --metrics path, the record covers the whole run: the same totals as an uninterrupted
// run, its rows once each, two segments.
TEST_F(ResumedRun, RestartedSolveContinuesTheRecordOfTheKilledRun) {
  const fs::path whole = dir_ / "whole", part = dir_ / "part";
  // Options from the environment are options the backend ran with: the record names them.
  setenv("PETSC_OPTIONS", "-lu_mumps_mat_mumps_icntl_14 40", 1);
  const CliRun straight = CliRun::of({"solve", scene_.string(), "--quiet", "--no-vtu", "--out", whole.string(),
                                      "--metrics", (whole / "metrics.toml").string()},
                                     dir_);
  unsetenv("PETSC_OPTIONS");
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  EXPECT_NE(run_table(whole / "metrics.toml")["backend_options"].value<std::string>().value_or("").find(
                "# PETSC_OPTIONS\n-lu_mumps_mat_mumps_icntl_14 40\n"),
            std::string::npos);

  fs::create_directories(part);
  ASSERT_TRUE(run_and_kill_after_first_step({"solve", scene_.string(), "--quiet", "--no-vtu", "--out", part.string(),
                                             "--metrics", (part / "metrics.toml").string()},
                                            part / "metrics.toml"))
      << "the run ended before it could be killed: " << read_file(dir_ / "killed.err");
  ASSERT_TRUE(fs::exists(part / "checkpoint.bin"));
  const int checkpoint_step = stiction::harness::read_checkpoint((part / "checkpoint.bin").string()).state.step;
  {
    const toml::table killed = run_table(part / "metrics.toml");
    EXPECT_EQ(killed["reason"].value<std::string>(), "INCOMPLETE");
    const int64_t recorded = killed["load_steps_completed"].value<int64_t>().value_or(0);
    EXPECT_GE(recorded, 1);
    EXPECT_LT(recorded, 40) << "the kill came after the run's end";
    // The record is written before the checkpoint: it holds the checkpoint's step, at most one more.
    EXPECT_GE(recorded, checkpoint_step);
    EXPECT_LE(recorded, checkpoint_step + 1);
  }

  const CliRun rest = CliRun::of({"solve", scene_.string(), "--quiet", "--no-vtu", "--restart", part.string(),
                                  "--metrics", (part / "metrics.toml").string()},
                                 dir_);
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  const toml::table a = run_table(part / "metrics.toml"), b = run_table(whole / "metrics.toml");
  EXPECT_EQ(a["reason"].value<std::string>(), "CONVERGED");
  EXPECT_EQ(a["segments"].value<int64_t>(), 2);
  EXPECT_EQ(b["segments"].value<int64_t>(), 1);
  for (const char* total : {"load_steps_completed", "newton_iterations", "linear_solves", "krylov_iterations"})
    EXPECT_EQ(a[total].value<int64_t>().value_or(-1), b[total].value<int64_t>().value_or(-2)) << total;
  const toml::table doc = toml::parse_file((part / "metrics.toml").string());
  ASSERT_TRUE(doc["step"].as_array());
  std::vector<int64_t> steps;
  for (const auto& row : *doc["step"].as_array()) steps.push_back((*row.as_table())["step"].value<int64_t>().value_or(0));
  ASSERT_EQ(steps.size(), 40u);
  for (size_t k = 0; k < steps.size(); ++k) EXPECT_EQ(steps[k], static_cast<int64_t>(k + 1)) << "row " << k;

  // A record of another backend is not continued into.
  const CliRun other = CliRun::of({"solve", scene_.string(), "--quiet", "--no-vtu", "--solver", "lu-umfpack",
                                   "--restart", part.string(), "--metrics", (part / "metrics.toml").string()},
                                  dir_);
  EXPECT_EQ(other.exit_code, 2) << other.err;
  EXPECT_EQ(other.error_lines().size(), 1u) << other.err;
  EXPECT_NE(other.err.find("give another --metrics path"), std::string::npos) << other.err;
}

// A sweep killed during a run: `bench --resume` continues that run from its checkpoint (its
// steps.csv says it restarted) and writes the row of the whole run, equal in its counts to the
// row of a sweep that was never interrupted.
TEST_F(ResumedRun, BenchResumeContinuesAnInterruptedRunFromItsCheckpoint) {
  const std::vector<std::string> bench = {"bench", "--scenes", scene_.string(), "--solvers", "lu-mumps", "--levels", "0"};
  std::vector<std::string> straight_args = bench;
  straight_args.insert(straight_args.end(), {"--out", (dir_ / "straight").string()});
  const CliRun straight = CliRun::of(straight_args, dir_);
  ASSERT_EQ(straight.exit_code, 0) << straight.err;

  // The interrupted sweep: its run killed after its first load steps, before any row.
  const fs::path run_dir = dir_ / "interrupted" / "runs" / "cantilever-40-L0-lu-mumps";
  fs::create_directories(run_dir);
  ASSERT_TRUE(run_and_kill_after_first_step({"solve", scene_.string(), "--level", "0", "--solver", "lu-mumps", "--out",
                                             run_dir.string(), "--quiet", "--no-vtu", "--metrics",
                                             (run_dir / "metrics.toml").string()},
                                            run_dir / "metrics.toml"))
      << read_file(dir_ / "killed.err");
  const int checkpoint_step = stiction::harness::read_checkpoint((run_dir / "checkpoint.bin").string()).state.step;

  std::vector<std::string> resume_args = bench;
  resume_args.insert(resume_args.end(), {"--out", (dir_ / "interrupted").string(), "--resume"});
  const CliRun resumed = CliRun::of(resume_args, dir_);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("continued from its checkpoint after load step " + std::to_string(checkpoint_step)),
            std::string::npos)
      << resumed.err;
  EXPECT_NE(read_file(run_dir / "steps.csv").find("# restarted from"), std::string::npos)
      << "the run started again instead of continuing";

  const auto a = stiction::harness::read_csv((dir_ / "interrupted" / "runs.csv").string()).rows;
  const auto b = stiction::harness::read_csv((dir_ / "straight" / "runs.csv").string()).rows;
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(a[0].at("status"), "ok");
  for (const char* column : {"load_steps_completed", "newton_iterations", "linear_solves", "krylov_iterations"})
    EXPECT_EQ(a[0].at(column), b[0].at(column)) << column;
  EXPECT_NE(a[0].at("detail").find("2 segments"), std::string::npos) << a[0].at("detail");
  EXPECT_GT(std::stod(a[0].at("peak_rss_mb")), 0.0);
  // Every linear solve of the run, once, in the sweep's steps.csv.
  const auto solves_a = stiction::harness::read_csv((dir_ / "interrupted" / "steps.csv").string()).rows;
  const auto solves_b = stiction::harness::read_csv((dir_ / "straight" / "steps.csv").string()).rows;
  EXPECT_EQ(solves_a.size(), solves_b.size());
}

// A sweep stopped after its run had ended but before it wrote the row: `bench --resume`
// writes the row from the run's own record and runs nothing again.
TEST_F(ResumedRun, BenchResumeWritesTheRowOfARunThatHadEnded) {
  const fs::path run_dir = dir_ / "stopped" / "runs" / "cantilever-40-L0-lu-mumps";
  fs::create_directories(run_dir);
  const CliRun run = CliRun::of({"solve", scene_.string(), "--level", "0", "--solver", "lu-mumps", "--out",
                                 run_dir.string(), "--quiet", "--no-vtu", "--metrics", (run_dir / "metrics.toml").string()},
                                dir_);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string steps_before = read_file(run_dir / "steps.csv");
  const CliRun resumed = CliRun::of({"bench", "--scenes", scene_.string(), "--solvers", "lu-mumps", "--levels", "0",
                                     "--out", (dir_ / "stopped").string(), "--resume"},
                                    dir_);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("had ended without its row"), std::string::npos) << resumed.err;
  EXPECT_EQ(read_file(run_dir / "steps.csv"), steps_before) << "the run was run again";
  const auto rows = stiction::harness::read_csv((dir_ / "stopped" / "runs.csv").string()).rows;
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("status"), "ok");
  EXPECT_EQ(rows[0].at("load_steps_completed"), "40");
  EXPECT_EQ(rows[0].at("newton_iterations"), "160");
  const toml::table record = run_table(run_dir / "metrics.toml");
  EXPECT_NEAR(std::stod(rows[0].at("wall_seconds")), record["wall_seconds"].value<double>().value_or(-1), 1e-3);
  EXPECT_NE(rows[0].at("detail").find("row from the run's record"), std::string::npos) << rows[0].at("detail");
}

}  // namespace
