#include "nonlinear/problem.hpp"

namespace stiction::nonlinear {

std::vector<double> uniform_step_times(int n_steps) {
  std::vector<double> t(static_cast<size_t>(n_steps) + 1);
  for (int k = 0; k <= n_steps; ++k) t[k] = static_cast<double>(k) / n_steps;
  return t;
}

int ElasticityProblem::step_reaching(double t) const {
  for (int k = 1; k <= n_steps(); ++k)
    if (step_times[k] >= t * (1 - 1e-12)) return k;
  return n_steps();
}

}  // namespace stiction::nonlinear
