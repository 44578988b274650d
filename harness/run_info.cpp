#include "run_info.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <thread>

#include "common/petsc.hpp"
#include "common/process_memory.hpp"

#ifndef STICTION_SOURCE_DIR
#define STICTION_SOURCE_DIR "."
#endif

namespace stiction::harness {

namespace {

std::string run(const std::string& cmd) {
  std::array<char, 256> buf{};
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return "";
  while (fgets(buf.data(), buf.size(), p)) out += buf.data();
  pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

std::string env_or(const char* name, const char* fallback) {
  const char* v = std::getenv(name);
  return v ? v : fallback;
}

// The processor's model and widest vector extension: OpenBLAS picks its kernels by them, so
// a factorisation's time depends on them far more than an iterative solve's.
std::string cpu_description() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU", simd = "no AVX";
  bool flags_read = false;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0 && model == "unknown CPU") model = line.substr(line.find(':') + 2);
    if (line.rfind("flags", 0) == 0 && !flags_read) {
      flags_read = true;
      const std::string flags = " " + line.substr(line.find(':') + 1) + " ";
      if (flags.find(" avx512f ") != std::string::npos) simd = "AVX-512";
      else if (flags.find(" avx2 ") != std::string::npos) simd = "AVX2";
      else if (flags.find(" avx ") != std::string::npos) simd = "AVX";
    }
  }
  const char* coretype = std::getenv("OPENBLAS_CORETYPE");
  return fmt::format("{} ({}{})", model, simd, coretype ? fmt::format(", OPENBLAS_CORETYPE={}", coretype) : "");
}

}  // namespace

RunInfo collect_run_info(int argc, char** argv) {
  RunInfo i;
  // Options from the environment change every backend's behaviour: part of the command.
  if (const char* env = std::getenv("PETSC_OPTIONS"); env && *env)
    i.command_line = fmt::format("PETSC_OPTIONS='{}' ", env);
  for (int k = 0; k < argc; ++k) i.command_line += (k ? " " : "") + std::string(argv[k]);
  // The revision the binary was built from; a binary copied away and run after further
  // commits says so, with the source tree's revision at run time.
  const std::string src = STICTION_SOURCE_DIR;
  i.git_revision = build_revision();
  std::string tree = run("git -C '" + src + "' rev-parse --short=12 HEAD 2>/dev/null");
  if (!tree.empty() && !run("git -C '" + src + "' status --porcelain --untracked-files=no 2>/dev/null").empty())
    tree += " with uncommitted changes";
  if (!tree.empty() && i.git_revision.rfind(tree.substr(0, 12), 0) != 0)
    i.git_revision += fmt::format(" (source tree at {} when run)", tree);
  i.petsc_version = petsc_version_string();
  std::error_code ec;
  auto blas = std::filesystem::canonical("/usr/lib/x86_64-linux-gnu/libblas.so.3", ec);
  i.blas = ec ? "unknown" : blas.string();
  i.threads = fmt::format("OMP_NUM_THREADS={} OPENBLAS_NUM_THREADS={}", env_or("OMP_NUM_THREADS", "unset"),
                          env_or("OPENBLAS_NUM_THREADS", "unset"));
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  i.machine = fmt::format("{} cores, {:.1f} GiB memory, {}", std::thread::hardware_concurrency(),
                          static_cast<double>(pages) * page / (1024.0 * 1024 * 1024), cpu_description());
  i.allocator = allocator_settings();
  std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&now));
  i.date = date;
  return i;
}

std::string format_run_info(const RunInfo& i, const std::string& p) {
  return fmt::format(
      "{0}command: {1}\n{0}git revision: {2}\n{0}PETSc: {3}\n{0}BLAS: {4} ({5})\n{0}machine: {6}\n{0}memory "
      "allocator: {7}\n{0}date: {8}\n",
      p, i.command_line, i.git_revision, i.petsc_version, i.blas, i.threads, i.machine, i.allocator, i.date);
}

}  // namespace stiction::harness
