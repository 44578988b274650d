// The summed Jacobian entries of one slave facet (merged_entries.hpp): every (row, column)
// pair once, with the sum of its values, in first-insertion order, against a std::map that
// sums the same stream; the table grows past its initial capacity and is reused after a flush.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>
#include <vector>

#include "contact/merged_entries.hpp"

namespace stiction::contact {
namespace {

struct Reference {
  std::map<std::pair<PetscInt, PetscInt>, double> sums;
  std::vector<std::pair<PetscInt, PetscInt>> first_seen;
  void add(PetscInt r, PetscInt c, double v) {
    const auto [it, inserted] = sums.try_emplace({r, c}, 0.0);
    if (inserted) first_seen.emplace_back(r, c);
    it->second += v;
  }
};

// A stream of n entries over about `keys` distinct pairs with large dof numbers, so that the
// pairs collide in the table and share rows and columns.
void add_random_stream(MergedEntries& merged, Reference& reference, int n, int keys, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_int_distribution<PetscInt> pick(0, keys - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int k = 0; k < n; ++k) {
    const PetscInt key = pick(gen);
    const PetscInt r = 2'000'000'000 - 7 * (key % 97), c = 3 * (key / 97);
    const double v = value(gen);
    merged.add(r, c, v);
    reference.add(r, c, v);
  }
}

void expect_flushed_equal(MergedEntries& merged, const Reference& reference) {
  nonlinear::SparseEntries out;
  merged.flush_into(out);
  ASSERT_EQ(out.size(), reference.first_seen.size());
  for (size_t k = 0; k < out.size(); ++k) {
    const auto pair = reference.first_seen[k];
    EXPECT_EQ(out.rows[k], pair.first) << k;
    EXPECT_EQ(out.cols[k], pair.second) << k;
    // The same additions in the same order: equal, not only close.
    EXPECT_EQ(out.values[k], reference.sums.at(pair)) << k;
  }
  EXPECT_EQ(merged.size(), 0u);
}

TEST(MergedEntries, SumsRepeatedPairsInFirstInsertionOrder) {
  MergedEntries merged;
  Reference reference;
  add_random_stream(merged, reference, 20000, 600, 1);
  ASSERT_LT(reference.first_seen.size(), 20000u);  // pairs did repeat
  EXPECT_EQ(merged.size(), reference.first_seen.size());
  expect_flushed_equal(merged, reference);
}

TEST(MergedEntries, GrowsPastItsCapacityKeepingTheSums) {
  MergedEntries merged(2);  // four slots: the stream below doubles the table many times
  Reference reference;
  add_random_stream(merged, reference, 5000, 3000, 2);
  ASSERT_GT(reference.first_seen.size(), 1000u);
  expect_flushed_equal(merged, reference);
}

TEST(MergedEntries, StartsFromZeroAfterAFlush) {
  MergedEntries merged;
  Reference first, second;
  add_random_stream(merged, first, 3000, 400, 3);
  expect_flushed_equal(merged, first);
  add_random_stream(merged, second, 3000, 400, 4);  // the same pairs again, new values
  expect_flushed_equal(merged, second);
}

}  // namespace
}  // namespace stiction::contact
