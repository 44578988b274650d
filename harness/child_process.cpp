#include "child_process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "common/error.hpp"
#include "common/process_memory.hpp"

extern char** environ;

namespace stiction::harness {

namespace {

bool is_launcher_variable(const char* entry) {
  for (const char* prefix : {"OMPI_", "PMIX_", "OPAL_", "PMI_"})
    if (std::strncmp(entry, prefix, std::strlen(prefix)) == 0) return true;
  return false;
}

}  // namespace

std::string self_executable() {
  std::error_code ec;
  auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("cannot locate the stiction executable (/proc/self/exe)", ErrorKind::Internal);
  return p.string();
}

double physical_memory_mb() {
  return static_cast<double>(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGE_SIZE) / (1024.0 * 1024.0);
}

ChildResult run_child(const std::vector<std::string>& argv, const std::string& stdout_path,
                      const std::string& stderr_path, const ChildLimits& limits,
                      const std::function<void(double)>& on_tick) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<char*> env;
  for (char** e = environ; *e; ++e)
    if (!is_launcher_variable(*e)) env.push_back(*e);
  env.push_back(nullptr);

  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw Error(fmt::format("fork failed: {}", std::strerror(errno)), ErrorKind::Internal);
  if (pid == 0) {
    const int out = open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out >= 0) dup2(out, STDOUT_FILENO);
    if (err >= 0) dup2(err, STDERR_FILENO);
    // /proc/self/exe is this very executable even if the file on disk has been replaced
    // meanwhile (a rebuild during a long sweep), so every run of a sweep uses one binary.
    execve("/proc/self/exe", args.data(), env.data());
    _exit(127);
  }

  ChildResult r;
  int status = 0;
  rusage usage{};
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    const double t = elapsed();
    if (!r.hit_time_limit && !r.hit_memory_limit) {
      if (t > limits.seconds) r.hit_time_limit = true;
      if (limits.memory_mb > 0 && proc_status_mb(pid, "VmRSS") > limits.memory_mb) r.hit_memory_limit = true;
      if (r.hit_time_limit || r.hit_memory_limit) kill(pid, SIGKILL);
    }
    if (on_tick) on_tick(t);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  r.wall_seconds = elapsed();
  r.peak_rss_mb = usage.ru_maxrss / 1024.0;
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
  return r;
}

std::string solve_status(const ChildResult& c, bool have_metrics) {
  if (c.hit_memory_limit) return "memory-limit";
  if (c.hit_time_limit) return "time-limit";
  if (c.signal) return c.signal == 9 ? "killed (signal 9; out of memory?)" : fmt::format("killed (signal {})", c.signal);
  if (c.exit_code == 0 && have_metrics) return "ok";
  if (c.exit_code == 3 && have_metrics) return "newton-failed";
  return "error";
}

ChildLimits sweep_limits(double seconds, double memory_mb) {
  const ChildLimits limits{seconds, memory_mb > 0 ? memory_mb : 0.9 * physical_memory_mb()};
  setenv("STICTION_MEMORY_LIMIT_MB", fmt::format("{:.0f}", limits.memory_mb).c_str(), 1);
  return limits;
}

}  // namespace stiction::harness
