#include "common/process_memory.hpp"

#include <fstream>
#include <string>

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

}  // namespace stiction
