#pragma once
// Runs the `stiction` executable as a child process for the CLI tests: exit code (128 +
// signal if it was killed) and captured stderr, with a timeout so a hang fails the test.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#ifndef STICTION_BINARY
#error "STICTION_BINARY (path of the stiction executable) must be defined by the build"
#endif

extern char** environ;

namespace stiction::test {

namespace fs = std::filesystem;

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// An environment variable (NAME=value) of this (PETSc-initialised) test process's MPI job: a
// child must not inherit it, so that it starts as its own MPI singleton instead of joining
// this process's PMIx job.
inline bool is_mpi_variable(const std::string& var) {
  return var.rfind("OMPI_", 0) == 0 || var.rfind("PMIX_", 0) == 0 || var.rfind("OPAL_", 0) == 0;
}

// `env -u NAME ...` for the MPI variables of this process.
inline std::string without_mpi_environment() {
  std::string prefix = "env";
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string var = *e;
    if (is_mpi_variable(var)) prefix += " -u " + var.substr(0, var.find('='));
  }
  return prefix;
}

// A fresh directory under the test's temporary directory (stem-XXXXXX); empty on failure.
inline fs::path make_temporary_directory(const std::string& stem) {
  std::string pattern = (fs::path(::testing::TempDir()) / (stem + "-XXXXXX")).string();
  return mkdtemp(pattern.data()) ? fs::path(pattern) : fs::path();
}

// One run of the binary: exit code (128 + signal if it was killed) and captured stderr.
struct CliRun {
  int exit_code = -1;
  std::string err;

  static constexpr int timeout_seconds = 300;  // `timeout` exits 124 if the run hangs

  static CliRun of(const std::vector<std::string>& args, const fs::path& workdir) {
    return of_command(shell_quote(STICTION_BINARY), args, workdir);
  }

  // `launcher` (the binary, or e.g. `mpirun -n 2 <binary>`) with args, run in workdir.
  static CliRun of_command(const std::string& launcher, const std::vector<std::string>& args,
                           const fs::path& workdir) {
    const fs::path err_file = workdir / "stderr.txt";
    std::string command = "cd " + shell_quote(workdir.string()) + " && exec " +
                          without_mpi_environment() + " timeout " +
                          std::to_string(timeout_seconds) + " " + launcher;
    for (const auto& a : args) command += " " + shell_quote(a);
    command += " >" + shell_quote((workdir / "stdout.txt").string()) + " 2>" +
               shell_quote(err_file.string());
    const int status = std::system(command.c_str());
    CliRun run;
    if (status != -1 && WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
    else if (status != -1 && WIFSIGNALED(status)) run.exit_code = 128 + WTERMSIG(status);
    run.err = read_file(err_file);
    return run;
  }

  std::vector<std::string> error_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);)
      if (line.rfind("stiction: error:", 0) == 0) lines.push_back(line);
    return lines;
  }
};

}  // namespace stiction::test
