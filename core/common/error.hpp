#pragma once
// One exception type for every user-facing failure: the CLI prints its message on one line
// and exits non-zero. `kind` selects the exit code so scripts can tell input errors from
// numerical failures.
#include <stdexcept>
#include <string>

namespace stiction {

enum class ErrorKind { Input = 2, Numerical = 3, Internal = 4 };

// Under MPI: whether every process meets the failure alike (bad input, a failure of the
// Newton state all processes share), so one message suffices, or possibly one process
// alone (anything else), which must then end the job.
enum class Reach { OneProcess, EveryProcess };

class Error : public std::runtime_error {
public:
  explicit Error(const std::string& what, ErrorKind kind = ErrorKind::Input, Reach reach = Reach::OneProcess)
      : std::runtime_error(what), kind_(kind), reach_(kind == ErrorKind::Input ? Reach::EveryProcess : reach) {}
  ErrorKind kind() const { return kind_; }
  Reach reach() const { return reach_; }

private:
  ErrorKind kind_;
  Reach reach_;
};

}  // namespace stiction
