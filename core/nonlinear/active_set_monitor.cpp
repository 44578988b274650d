#include "nonlinear/active_set_monitor.hpp"

namespace stiction::nonlinear {

bool ActiveSetMonitor::may_update(double progress, bool converged) {
  if (converged || gate_ <= 0 || progress <= gate_ || held_ >= settings_.max_held) {
    held_ = 0;
    return true;
  }
  ++held_;
  return false;
}

ActiveSetMonitor::Verdict ActiveSetMonitor::after_update(const std::vector<char>& before, const std::vector<char>& now,
                                                         double left_at, double residual_now) {
  if (before == now) return Verdict::Continue;
  seen_[before] = left_at;
  const auto seen = seen_.find(now);
  if (seen == seen_.end() || residual_now < seen->second) return Verdict::Continue;
  if (remedies_ == settings_.cycle_remedies) return Verdict::Cycle;
  ++remedies_;
  // gate_ is 0 only under the paper's rule (update_tolerance 0); a cycle then opens a gate.
  gate_ = (gate_ > 0 ? gate_ : 1e-3) * settings_.remedy_factor;
  seen_.clear();
  return Verdict::Remedied;
}

}  // namespace stiction::nonlinear
