#include "stdout_capture.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

namespace stiction::solvers {

StdoutCapture::StdoutCapture() {
  char tmpl[] = "/tmp/stiction-stdout-XXXXXX";
  const int fd = mkstemp(tmpl);
  if (fd < 0) return;
  path_ = tmpl;
  std::fflush(stdout);
  saved_fd_ = dup(STDOUT_FILENO);
  if (saved_fd_ < 0 || dup2(fd, STDOUT_FILENO) < 0) {
    close(fd);
    return;
  }
  close(fd);
  active_ = true;
}

void StdoutCapture::restore() {
  if (!active_) return;
  std::fflush(stdout);
  dup2(saved_fd_, STDOUT_FILENO);
  close(saved_fd_);
  active_ = false;
}

std::string StdoutCapture::text() {
  restore();
  std::ifstream in(path_);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

StdoutCapture::~StdoutCapture() {
  restore();
  if (!path_.empty()) std::remove(path_.c_str());
}

double parse_operator_complexity(const std::string& text) {
  static const std::regex re(R"(operator\s*=\s*([0-9]*\.?[0-9]+))");
  double value = -1;
  for (std::sregex_iterator it(text.begin(), text.end(), re), end; it != end; ++it) value = std::stod((*it)[1]);
  return value;
}

}  // namespace stiction::solvers
