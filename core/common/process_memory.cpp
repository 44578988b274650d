#include "common/process_memory.hpp"

#include <fmt/format.h>
#include <malloc.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "common/error.hpp"

namespace stiction {

double proc_status_mb(int pid, const char* field) {
  std::ifstream status(pid ? "/proc/" + std::to_string(pid) + "/status" : std::string("/proc/self/status"));
  const std::string wanted = std::string(field) + ":";
  std::string key;
  while (status >> key) {
    if (key == wanted) {
      double kb = 0;
      status >> kb;
      return kb / 1024.0;
    }
    std::getline(status, key);
  }
  return 0;
}

namespace {

// Blocks of at least this size are mapped on their own; a heap whose free top exceeds twice
// it is trimmed (glibc's own dynamic rule keeps the trim threshold at twice the mapping one).
// STICTION_MMAP_THRESHOLD_MB, 1 by default, within what glibc's mallopt accepts (it refuses
// thresholds above 32 MB on 64-bit systems). 1 MB puts a vector of a few hundred thousand
// unknowns (a Krylov basis vector at level 1 of the block with strips is 2.8 MB) in its own
// mapping: a basis freed before the next assembly is then returned rather than held in the
// heap while that assembly and set-up allocate theirs, which set the run's peak
// (docs/method.md, "Choices beyond the paper").
std::size_t mapped_block_bytes() {
  const char* given = std::getenv("STICTION_MMAP_THRESHOLD_MB");
  if (!given) return std::size_t{1} << 20;
  char* end = nullptr;
  const double mb = std::strtod(given, &end);
  if (end == given || *end != '\0' || !(mb >= 0.125 && mb <= 32))
    throw Error(fmt::format("STICTION_MMAP_THRESHOLD_MB must be a size in MB from 0.125 to 32, not '{}'", given),
                ErrorKind::Input);
  return static_cast<std::size_t>(mb * 1048576.0);
}

bool hold_freed_memory() {
  const char* hold = std::getenv("STICTION_HOLD_FREED_MEMORY");
  return hold && std::string(hold) == "1";
}

}  // namespace

void return_freed_memory_to_the_system() {
  if (hold_freed_memory()) return;
  const std::size_t bytes = mapped_block_bytes();
  mallopt(M_MMAP_MAX, 65536);  // glibc's default
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(bytes));
  mallopt(M_TRIM_THRESHOLD, static_cast<int>(2 * bytes));
}

void restart_with_huge_pages_for_mapped_blocks(char** argv) {
  if (hold_freed_memory()) return;
  const char* given = std::getenv("GLIBC_TUNABLES");
  const std::string tunables = given ? given : "";
  if (tunables.find("glibc.malloc.hugetlb") != std::string::npos) return;
  const std::string with = (tunables.empty() ? "" : tunables + ":") + "glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", with.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not re-executed (no /proc): the same run with 4 kB pages.
  if (given) setenv("GLIBC_TUNABLES", given, 1);
  else unsetenv("GLIBC_TUNABLES");
}

std::string allocator_settings() {
  if (hold_freed_memory()) return "glibc malloc, freed memory held (STICTION_HOLD_FREED_MEMORY=1)";
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string thp_modes;
  std::getline(thp, thp_modes);
  const double mb = mapped_block_bytes() / 1048576.0;
  return fmt::format(
      "glibc malloc, blocks of {:g} MB and more mapped on their own, heap trimmed above {:g} MB; GLIBC_TUNABLES={}; "
      "transparent huge pages: {}",
      mb, 2 * mb, tunables ? tunables : "unset", thp_modes.empty() ? "unknown" : thp_modes);
}

}  // namespace stiction
