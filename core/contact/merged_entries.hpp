#pragma once
// Sums of repeated (row, column) Jacobian entries before they join a triplet list.
//
// One slave facet's contact points repeat the same (row, column) pairs many times (every
// master dof against every unknown that moves the master point, at each of the 36 points of a
// 3D facet); summing them before the triplet list keeps that list, and the augmented matrix's
// build from it, short. The sums are flushed once per facet, so the table is an open-addressing
// one with linear probing over flat arrays that keep their capacity: no allocation per new key
// and none freed at each flush, where a std::unordered_map allocates and frees a node per key.
// Flushed in first-insertion order, so the triplets' order does not depend on the hash.
#include <cstdint>
#include <vector>

#include <petscsys.h>

#include "nonlinear/multiplier_constraint.hpp"

namespace stiction::contact {

class MergedEntries {
public:
  explicit MergedEntries(int log2_capacity = 12) { resize(log2_capacity); }

  void add(PetscInt row, PetscInt col, double value) {
    const std::uint64_t key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(row)) << 32) |
                              static_cast<std::uint32_t>(col);
    std::size_t slot = home(key);
    while (keys_[slot] != key) {
      if (keys_[slot] == kEmpty) {
        // Keep the load at most one half, so that probes stay short.
        if (2 * (used_.size() + 1) > keys_.size()) {
          grow();
          add(row, col, value);
          return;
        }
        keys_[slot] = key;
        values_[slot] = 0.0;
        used_.push_back(slot);
        break;
      }
      slot = (slot + 1) & mask_;
    }
    values_[slot] += value;
  }

  std::size_t size() const { return used_.size(); }

  // Appends the sums to out and empties the table (its capacity stays).
  void flush_into(nonlinear::SparseEntries& out) {
    for (const std::size_t slot : used_) {
      out.add(static_cast<PetscInt>(keys_[slot] >> 32), static_cast<PetscInt>(keys_[slot] & 0xffffffffu),
              values_[slot]);
      keys_[slot] = kEmpty;
    }
    used_.clear();
  }

private:
  // Rows and columns are non-negative PetscInt (32-bit), so no entry's key has both halves
  // all ones.
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  std::size_t home(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
  }

  void resize(int log2_capacity) {
    keys_.assign(std::size_t{1} << log2_capacity, kEmpty);
    values_.assign(keys_.size(), 0.0);
    mask_ = keys_.size() - 1;
    shift_ = 64 - log2_capacity;
    log2_capacity_ = log2_capacity;
  }

  // Doubles the table and re-inserts the sums in their first-insertion order.
  void grow() {
    std::vector<std::uint64_t> keys;
    std::vector<double> values;
    keys.reserve(used_.size());
    values.reserve(used_.size());
    for (const std::size_t slot : used_) keys.push_back(keys_[slot]), values.push_back(values_[slot]);
    resize(log2_capacity_ + 1);
    used_.clear();
    for (std::size_t k = 0; k < keys.size(); ++k)
      add(static_cast<PetscInt>(keys[k] >> 32), static_cast<PetscInt>(keys[k] & 0xffffffffu), values[k]);
  }

  std::vector<std::uint64_t> keys_;
  std::vector<double> values_;
  std::vector<std::size_t> used_;  // occupied slots, in first-insertion order
  std::size_t mask_ = 0;
  int shift_ = 64;
  int log2_capacity_ = 0;
};

}  // namespace stiction::contact
