// The augmented Newton matrix (nonlinear/augmented_matrix.hpp) built in the tangent's own
// value array: entry by entry it is the tangent plus the constraint entries (duplicates
// summed, a diagonal on every multiplier row), and no second value array is made.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "nonlinear/augmented_matrix.hpp"

namespace stiction::nonlinear {
namespace {

// A random sparse n x n tangent in compressed rows (sorted columns, diagonal present).
CsrArrays random_tangent(PetscInt n, std::mt19937& rng, std::map<std::pair<PetscInt, PetscInt>, double>& dense) {
  std::uniform_int_distribution<PetscInt> col(0, n - 1);
  std::uniform_real_distribution<double> value(-1, 1);
  auto start = std::make_shared<std::vector<PetscInt>>(1, 0);
  auto cols = std::make_shared<std::vector<PetscInt>>();
  auto vals = std::make_shared<std::vector<PetscScalar>>();
  for (PetscInt r = 0; r < n; ++r) {
    std::map<PetscInt, double> row{{r, 4.0}};
    for (int k = 0; k < 3; ++k) row[col(rng)] = value(rng);
    for (const auto& [c, v] : row) cols->push_back(c), vals->push_back(v), dense[{r, c}] += v;
    start->push_back(static_cast<PetscInt>(cols->size()));
  }
  vals->reserve(vals->size() * 4);  // room to merge in place, as StiffnessMatrix reserves
  return {start, cols, vals};
}

TEST(AugmentedMatrix, IsTheTangentPlusTheConstraintEntriesInTheTangentsValueArray) {
  std::mt19937 rng(5);
  const PetscInt n = 40, m = 9;
  std::map<std::pair<PetscInt, PetscInt>, double> expected;
  CsrArrays tangent = random_tangent(n, rng, expected);
  const PetscScalar* tangent_values = tangent.values->data();
  SparseEntries extra;
  std::uniform_int_distribution<PetscInt> u(0, n - 1), l(n, n + m - 1);
  std::uniform_real_distribution<double> value(-1, 1);
  for (int k = 0; k < 60; ++k) {
    const PetscInt a = u(rng), b = l(rng), c = u(rng);
    const double v1 = value(rng), v2 = value(rng), v3 = value(rng);
    extra.add(a, b, v1), expected[{a, b}] += v1;  // (u, lambda)
    extra.add(b, a, v2), expected[{b, a}] += v2;  // (lambda, u)
    extra.add(a, c, v3), expected[{a, c}] += v3;  // inside or beside the tangent's pattern
  }
  extra.add(n + 2, n + 2, 0.5), expected[{n + 2, n + 2}] += 0.5;
  extra.add(n + 2, n + 2, 0.25), expected[{n + 2, n + 2}] += 0.25;  // duplicates are summed
  for (PetscInt r = n; r < n + m; ++r) expected[{r, r}] += 0.0;      // every multiplier row has its diagonal

  PetscMat M(build_augmented_matrix(PETSC_COMM_WORLD, tangent, m, extra, 1));
  PetscInt rows, cols;
  MatGetSize(M, &rows, &cols);
  ASSERT_EQ(rows, n + m);
  ASSERT_EQ(cols, n + m);
  MatInfo info;
  MatGetInfo(M, MAT_LOCAL, &info);
  EXPECT_EQ(static_cast<size_t>(info.nz_used), expected.size());  // exactly the union of the patterns
  for (const auto& [rc, v] : expected) {
    PetscScalar got;
    MatGetValues(M, 1, &rc.first, 1, &rc.second, &got);
    EXPECT_NEAR(got, v, 1e-14) << "entry (" << rc.first << ", " << rc.second << ")";
  }
  const PetscScalar* values;
  MatSeqAIJGetArrayRead(M, &values);
  EXPECT_EQ(values, tangent_values);  // merged in place: no second value array
  MatSeqAIJRestoreArrayRead(M, &values);
}

}  // namespace
}  // namespace stiction::nonlinear
