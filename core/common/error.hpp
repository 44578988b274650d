#pragma once
// One exception type for every user-facing failure: the CLI prints its message on one line
// and exits non-zero. `kind` selects the exit code so scripts can tell input errors from
// numerical failures.
#include <stdexcept>
#include <string>

namespace stiction {

enum class ErrorKind { Input = 2, Numerical = 3, Internal = 4 };

class Error : public std::runtime_error {
public:
  explicit Error(const std::string& what, ErrorKind kind = ErrorKind::Input)
      : std::runtime_error(what), kind_(kind) {}
  ErrorKind kind() const { return kind_; }

private:
  ErrorKind kind_;
};

}  // namespace stiction
