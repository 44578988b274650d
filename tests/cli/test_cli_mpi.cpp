// stiction launched by mpirun on two processes: every command is refused with one message
// from rank 0 and exit code 2 (input), before any work, and bad input still names its cause
// once; no process is left running (each run is under `timeout`, which exits 124 on a hang).
// Labelled `mpi` (ctest -L mpi).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_run.hpp"

namespace {

namespace fs = std::filesystem;
using stiction::test::CliRun;
using stiction::test::shell_quote;

constexpr int kExitInput = 2;

// mpirun on PATH (openmpi-bin, installed with the build dependencies).
std::string find_mpirun() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  for (size_t start = 0; start <= dirs.size();) {
    const size_t end = dirs.find(':', start);
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / "mpirun";
    if (fs::exists(candidate)) return candidate.string();
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return {};
}

class StictionUnderMpirun : public ::testing::Test {
protected:
  void SetUp() override {
    mpirun_ = find_mpirun();
    ASSERT_FALSE(mpirun_.empty()) << "mpirun is not on PATH (Debian package openmpi-bin)";
    std::string pattern = (fs::path(::testing::TempDir()) / "stiction-mpi-XXXXXX").string();
    ASSERT_NE(mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  CliRun run(int processes, const std::vector<std::string>& args) const {
    // Open MPI refuses root without these; --oversubscribe: a CI machine may have one core.
    std::string launcher = shell_quote(mpirun_) + " -n " + std::to_string(processes) + " --oversubscribe";
    if (geteuid() == 0) launcher += " --allow-run-as-root";
    return CliRun::of_command(launcher + " " + shell_quote(STICTION_BINARY), args, dir_);
  }

  std::string mpirun_;
  fs::path dir_;
};

TEST_F(StictionUnderMpirun, SolveOnTwoProcessesIsRefusedOnceBeforeAnyWork) {
  const CliRun r = run(2, {"solve", "cantilever-2d", "--quiet", "--no-vtu", "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.exit_code, kExitInput) << r.err;
  ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
  EXPECT_NE(r.error_lines()[0].find("runs on one MPI process (launched on 2)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "steps.csv")) << "the refused run wrote results";
}

TEST_F(StictionUnderMpirun, OneProcessUnderMpirunSolves) {
  const CliRun r = run(1, {"solve", "cantilever-2d", "--quiet", "--no-vtu", "--out", (dir_ / "out").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.error_lines().empty()) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "steps.csv"));
}

TEST_F(StictionUnderMpirun, BadInputOnTwoProcessesGivesOneMessage) {
  const CliRun missing = run(2, {"solve", (dir_ / "no-such-scene.toml").string(), "--quiet"});
  EXPECT_EQ(missing.exit_code, kExitInput) << missing.err;
  EXPECT_EQ(missing.error_lines().size(), 1u) << missing.err;

  const CliRun unknown_option = run(2, {"solve", "cantilever-2d", "--no-such-option"});
  EXPECT_EQ(unknown_option.exit_code, kExitInput) << unknown_option.err;
  EXPECT_EQ(unknown_option.err.find("no-such-option"), unknown_option.err.rfind("no-such-option"))
      << "the usage error was printed by more than one process:\n"
      << unknown_option.err;
  EXPECT_NE(unknown_option.err.find("no-such-option"), std::string::npos) << unknown_option.err;
}

TEST_F(StictionUnderMpirun, SweepOnTwoProcessesIsRefusedOnce) {
  const CliRun r = run(2, {"bench", "--scenes", "cantilever-2d", "--solvers", "lu-mumps", "--quick", "--out",
                           (dir_ / "sweep").string()});
  EXPECT_EQ(r.exit_code, kExitInput) << r.err;
  ASSERT_EQ(r.error_lines().size(), 1u) << r.err;
  EXPECT_NE(r.error_lines()[0].find("`stiction bench` runs on one MPI process"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "sweep" / "runs.csv")) << "the refused sweep started runs";
}

}  // namespace
