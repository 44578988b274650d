#pragma once
// Captures what C code prints on stdout (hypre's BoomerAMG set-up statistics) for the
// lifetime of the object. hypre gives no API through PETSc for its operator complexity, so
// the AMG backends read it from the statistics hypre prints at set-up.
#include <string>

namespace stiction::solvers {

class StdoutCapture {
public:
  StdoutCapture();
  ~StdoutCapture();  // restores stdout
  StdoutCapture(const StdoutCapture&) = delete;
  StdoutCapture& operator=(const StdoutCapture&) = delete;
  std::string text();  // restores stdout and returns what was captured

private:
  void restore();
  int saved_fd_ = -1;
  std::string path_;
  bool active_ = false;
};

// "operator = 1.75" in hypre's set-up statistics; the last one if several AMG set-ups
// printed; negative if none.
double parse_operator_complexity(const std::string& hypre_output);

}  // namespace stiction::solvers
