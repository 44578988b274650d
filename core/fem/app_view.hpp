#pragma once
// Values of the Newton system's unknowns addressed by their app index (dof_layout.hpp's
// order: displacement node by node, then pressures, then multipliers), whatever holds them.
// (Over a mesh part the index is the part space's own dof, fem::DofLayout's local index.)
//
// Assembly, contact and the constraints read the state u and add into residuals through
// this view rather than through a std::vector indexed by app unknown, so that the storage
// may be either a whole vector (entry k is unknown k: one process, or every process holding
// everything) or one process's owned and ghost unknowns with a map from app index to
// storage index (ghosted storage on several processes). On the whole-vector path the view
// is a pointer and an index, and operator[] costs one well-predicted branch.
//
// A view does not own what it shows; it must not outlive the vector or map behind it. A
// default-constructed view shows nothing and converts to false (an optional output).
#include <cassert>
#include <cstddef>
#include <span>
#include <type_traits>
#include <vector>

namespace stiction::fem {

template <class T>
class AppView {
public:
  using value_type = std::remove_const_t<T>;

  AppView() = default;
  // A whole vector: unknown k is entry k.
  AppView(std::vector<value_type>& whole)  // NOLINT: implicit
      : data_(whole.data()), size_(whole.size()), stored_(whole.size()) {}
  template <class U = T, class = std::enable_if_t<std::is_const_v<U>>>
  AppView(const std::vector<value_type>& whole)  // NOLINT: implicit
      : data_(whole.data()), size_(whole.size()), stored_(whole.size()) {}
  // Storage of part of the unknowns (n_stored entries): unknown k is
  // storage[storage_of_app[k]] (n_app entries in the map; -1 where the storage does not hold
  // the unknown).
  AppView(T* storage, std::size_t n_stored, const int* storage_of_app, std::size_t n_app)
      : data_(storage), map_(storage_of_app), size_(n_app), stored_(n_stored) {}
  // A writable view read through.
  template <class U = T, class = std::enable_if_t<std::is_const_v<U>>>
  AppView(const AppView<value_type>& v)  // NOLINT: implicit
      : data_(v.data_), map_(v.map_), size_(v.size_), stored_(v.stored_) {}

  T& operator[](std::size_t app) const {
    assert(app < size_);
    if (!map_) return data_[app];
    assert(map_[app] >= 0);
    return data_[map_[app]];
  }
  // Whether the storage holds unknown k.
  bool holds(std::size_t app) const { return !map_ || map_[app] >= 0; }
  // The number of app unknowns addressed (not the number stored).
  std::size_t size() const { return size_; }
  explicit operator bool() const { return data_ != nullptr; }
  // Whether unknown k is entry k of the storage.
  bool whole() const { return map_ == nullptr; }
  // The map from app index to storage index (null when whole()): with storage().size(), what
  // addresses a copy of the storage the same way.
  const int* storage_map() const { return map_; }
  // What the view stores, in storage order (app order when whole()): two views of one
  // layout hold the same values when their storages are equal.
  std::span<T> storage() const { return {data_, stored_}; }

private:
  template <class>
  friend class AppView;
  T* data_ = nullptr;
  const int* map_ = nullptr;
  std::size_t size_ = 0, stored_ = 0;
};

// Read access to the state, and write access to a residual, by app index.
using StateView = AppView<const double>;
using ResidualView = AppView<double>;

}  // namespace stiction::fem
