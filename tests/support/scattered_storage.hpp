#pragma once
// A whole app-ordered vector copied into storage of another order with a map from app
// index to storage index (a random permutation into a few more slots than unknowns, the
// spare slots holding a poison value): what a process's owned-and-ghost storage looks like
// to a fem::AppView. Code that reads or writes through the view and not the whole vector
// gives, back through whole(), exactly what it gives on the whole vector.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "fem/app_view.hpp"

namespace stiction::test {

class ScatteredStorage {
public:
  explicit ScatteredStorage(const std::vector<double>& whole, unsigned seed = 11) : map_(whole.size()) {
    std::vector<int> slots(whole.size() + kSpare);
    std::iota(slots.begin(), slots.end(), 0);
    std::shuffle(slots.begin(), slots.end(), std::mt19937(seed));
    storage_.assign(slots.size(), kPoison);
    for (size_t k = 0; k < whole.size(); ++k) {
      map_[k] = slots[k];
      storage_[static_cast<size_t>(slots[k])] = whole[k];
    }
  }
  fem::StateView view() const { return {storage_.data(), storage_.size(), map_.data(), map_.size()}; }
  fem::ResidualView view() { return {storage_.data(), storage_.size(), map_.data(), map_.size()}; }
  // Back in app order.
  std::vector<double> whole() const {
    std::vector<double> out(map_.size());
    for (size_t k = 0; k < map_.size(); ++k) out[k] = storage_[static_cast<size_t>(map_[k])];
    return out;
  }
  // The spare slots still hold the poison (nothing wrote outside the map).
  bool spare_untouched() const {
    int poisoned = 0;
    for (double v : storage_) poisoned += v == kPoison;
    return poisoned == kSpare;
  }

private:
  static constexpr int kSpare = 5;
  static constexpr double kPoison = -7.25e300;
  std::vector<int> map_;
  std::vector<double> storage_;
};

}  // namespace stiction::test
