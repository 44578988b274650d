#pragma once
// Loads as functions of pseudo-time: a vector-valued piecewise-linear function given by rows
// (t_k, v_k) with increasing t_k, held constant before the first row and after the last.
// Scenes give it as a table or as a factor per load step (the step's pseudo-time is t_k);
// between rows, a cut-back increment sees the linear interpolation.
#include <vector>

namespace stiction::nonlinear {

class PiecewiseLinear {
public:
  // Throws when the times do not increase strictly or a row's size differs from the first's.
  PiecewiseLinear(std::vector<double> times, std::vector<std::vector<double>> values);
  // values at t (size() entries).
  void operator()(double t, double* out) const;
  int size() const { return static_cast<int>(values_.front().size()); }

private:
  std::vector<double> times_;
  std::vector<std::vector<double>> values_;
};

}  // namespace stiction::nonlinear
