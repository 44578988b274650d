#include "child_process.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>
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

// The process and its descendants (an MPI launcher's ranks), from /proc's parent links.
std::vector<pid_t> process_tree(pid_t root) {
  std::map<pid_t, std::vector<pid_t>> children;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(entry.path() / "stat");
    std::string text;
    std::getline(stat, text);
    const auto close = text.rfind(')');  // the command name may hold spaces and parentheses
    if (close == std::string::npos) continue;
    std::istringstream rest(text.substr(close + 1));
    std::string state;
    pid_t parent = 0;
    if (rest >> state >> parent) children[parent].push_back(static_cast<pid_t>(std::stol(name)));
  }
  std::vector<pid_t> tree{root};
  for (size_t k = 0; k < tree.size(); ++k)
    for (pid_t c : children[tree[k]]) tree.push_back(c);
  return tree;
}

double tree_resident_mb(const std::vector<pid_t>& tree) {
  double mb = 0;
  for (pid_t p : tree) mb += std::max(proc_status_mb(p, "VmRSS"), 0.0);
  return mb;
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
                      const std::function<void(double)>& on_tick, const std::vector<std::string>& launcher) {
  std::vector<std::string> command = launcher;
  if (!launcher.empty()) {
    command.push_back(self_executable());
    command.insert(command.end(), argv.begin() + 1, argv.end());
  }
  std::vector<char*> args;
  for (const auto& a : launcher.empty() ? argv : command) args.push_back(const_cast<char*>(a.c_str()));
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
    if (launcher.empty()) {
      execve("/proc/self/exe", args.data(), env.data());
    } else {
      environ = env.data();
      execvp(args[0], args.data());
    }
    _exit(127);
  }

  ChildResult r;
  int status = 0;
  rusage usage{};
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  double tree_peak_mb = 0;  // the launcher and its ranks together, as polled
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    if (done == pid) break;
    const double t = elapsed();
    const std::vector<pid_t> tree = launcher.empty() ? std::vector<pid_t>{pid} : process_tree(pid);
    const double resident = tree_resident_mb(tree);
    tree_peak_mb = std::max(tree_peak_mb, resident);
    if (!r.hit_time_limit && !r.hit_memory_limit) {
      if (t > limits.seconds) r.hit_time_limit = true;
      if (limits.memory_mb > 0 && resident > limits.memory_mb) r.hit_memory_limit = true;
      if (r.hit_time_limit || r.hit_memory_limit)
        for (auto it = tree.rbegin(); it != tree.rend(); ++it) kill(*it, SIGKILL);
    }
    if (on_tick) on_tick(t);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  r.wall_seconds = elapsed();
  r.peak_rss_mb = std::max(usage.ru_maxrss / 1024.0, launcher.empty() ? 0.0 : tree_peak_mb);
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
