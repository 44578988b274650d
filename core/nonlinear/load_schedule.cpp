#include "nonlinear/load_schedule.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/error.hpp"

namespace stiction::nonlinear {

PiecewiseLinear::PiecewiseLinear(std::vector<double> times, std::vector<std::vector<double>> values)
    : times_(std::move(times)), values_(std::move(values)) {
  if (times_.empty() || times_.size() != values_.size())
    throw Error(fmt::format("a load table needs at least one row ({} times, {} values)", times_.size(),
                            values_.size()));
  for (size_t k = 0; k < times_.size(); ++k) {
    if (values_[k].size() != values_[0].size() || values_[0].empty())
      throw Error(fmt::format("load table row {} has {} values where the first has {}", k, values_[k].size(),
                              values_[0].size()));
    if (k > 0 && !(times_[k] > times_[k - 1]))
      throw Error(fmt::format("load table: pseudo-times must increase (row {}: {} after {})", k, times_[k],
                              times_[k - 1]));
  }
}

void PiecewiseLinear::operator()(double t, double* out) const {
  const size_t n = values_[0].size();
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  if (after == times_.begin() || after == times_.end()) {
    const auto& v = after == times_.begin() ? values_.front() : values_.back();
    std::copy(v.begin(), v.end(), out);
    return;
  }
  const size_t k = static_cast<size_t>(after - times_.begin());
  const double w = (t - times_[k - 1]) / (times_[k] - times_[k - 1]);
  for (size_t c = 0; c < n; ++c) out[c] = (1 - w) * values_[k - 1][c] + w * values_[k][c];
}

}  // namespace stiction::nonlinear
