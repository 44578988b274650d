// A slave facet's derivative columns summed before the nodes' maps (facet_columns.hpp): the
// nodes' maps equal those of adding every contribution to them directly (to round-off: the
// sums are grouped differently), a node given as null receives nothing, and the table starts
// empty after each flush.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "contact/facet_columns.hpp"

namespace stiction::contact {
namespace {

void expect_same_columns(const std::map<PetscInt, Vec3>& got, const std::map<PetscInt, Vec3>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (const auto& [dof, column] : want) {
    ASSERT_TRUE(got.count(dof)) << "dof " << dof;
    EXPECT_LT((got.at(dof) - column).norm(), 1e-13 * (1 + column.norm())) << "dof " << dof;
  }
}

TEST(FacetColumns, SumsEachVertexNodesColumnsAsTheMapsWould) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<PetscInt> dof(0, 59);
  std::uniform_int_distribution<int> vertex(0, 2);
  std::uniform_real_distribution<double> value(-1, 1);
  FacetColumns columns(60);
  NodeKinematics summed[3], direct[3];
  for (int facet = 0; facet < 3; ++facet) {  // three facets through one table
    for (int n = 0; n < 500; ++n) {
      const int k = vertex(rng);
      const PetscInt d = dof(rng);
      const Vec3 g(value(rng), value(rng), value(rng)), s(value(rng), value(rng), value(rng));
      columns.add(k, d, g, s);
      if (k == 2) continue;  // vertex 2's node is not derived below
      direct[k].dG.try_emplace(d, Vec3::Zero()).first->second += g;
      direct[k].dS.try_emplace(d, Vec3::Zero()).first->second += s;
    }
    columns.flush(3, [&](int k) { return k == 2 ? nullptr : &summed[k]; });
  }
  for (int k = 0; k < 2; ++k) {
    expect_same_columns(summed[k].dG, direct[k].dG);
    expect_same_columns(summed[k].dS, direct[k].dS);
  }
  EXPECT_TRUE(summed[2].dG.empty() && summed[2].dS.empty());
  // After the flushes the table is empty: a flush with nothing added adds nothing.
  NodeKinematics after;
  columns.flush(3, [&](int) { return &after; });
  EXPECT_TRUE(after.dG.empty() && after.dS.empty());
}

}  // namespace
}  // namespace stiction::contact
