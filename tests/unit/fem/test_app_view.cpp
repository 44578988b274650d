// fem::AppView: the assembly reads the state and adds into the residual through the view, so
// storage in another order with a map (a process's owned and ghost unknowns) gives exactly
// what a whole app-ordered vector gives.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "builtin_scenes.hpp"
#include "fem/app_view.hpp"
#include "fem/elasticity_assembly.hpp"
#include "fem/stiffness_matrix.hpp"
#include "scene/scene.hpp"
#include "support/scattered_storage.hpp"

namespace stiction::fem {
namespace {

TEST(AppView, AddressesStorageThroughItsMap) {
  const std::vector<double> whole = {1.5, -2.0, 3.25, 4.0};
  test::ScatteredStorage scattered(whole);
  ResidualView writable = scattered.view();
  ASSERT_FALSE(writable.whole());
  EXPECT_EQ(writable.size(), whole.size());
  EXPECT_EQ(writable.storage().size(), whole.size() + 5);
  const StateView readable = writable;
  for (size_t k = 0; k < whole.size(); ++k) EXPECT_EQ(readable[k], whole[k]);
  writable[1] += 5;
  EXPECT_EQ(scattered.whole()[1], 3.0);
  EXPECT_EQ(readable[1], 3.0);
  EXPECT_TRUE(scattered.spare_untouched());
  // A whole vector is its own storage; an empty view is no output.
  const StateView direct = whole;
  EXPECT_TRUE(direct.whole());
  EXPECT_EQ(direct.storage().data(), whole.data());
  EXPECT_TRUE(static_cast<bool>(writable));
  EXPECT_FALSE(static_cast<bool>(ResidualView()));
}

// Residual, tangent, boundary force and stress of a mixed u-p Mooney-Rivlin block (the
// pressure unknowns are read too) at a random state, once from whole vectors and once
// through scattered storage: bit for bit the same.
TEST(AppView, AssemblyThroughScatteredStorageMatchesTheWholeVector) {
  auto s = scene::build_scene(harness::builtin_scenes().at("mooney-rivlin-block"), "mooney-rivlin-block", ".", 0);
  const FieldSpace& space = *s->space;
  const auto& materials = s->problem.cell_material;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-0.05, 0.05);
  std::vector<double> u(space.n_dofs());
  for (double& v : u) v = U(rng);

  std::vector<double> r_whole(space.n_dofs(), 0.0);
  StiffnessMatrix K_whole(PETSC_COMM_WORLD, space);
  K_whole.begin_assembly();
  const InternalForceStatus status_whole = assemble_internal(space, materials, u, r_whole, &K_whole);
  K_whole.end_assembly();
  ASSERT_EQ(status_whole.inverted_cell, -1);

  const test::ScatteredStorage state(u);
  test::ScatteredStorage residual(std::vector<double>(space.n_dofs(), 0.0));
  StiffnessMatrix K_view(PETSC_COMM_WORLD, space);
  K_view.begin_assembly();
  const InternalForceStatus status_view = assemble_internal(space, materials, state.view(), residual.view(), &K_view);
  K_view.end_assembly();

  EXPECT_EQ(status_view.min_det_f, status_whole.min_det_f);
  EXPECT_EQ(residual.whole(), r_whole);
  EXPECT_TRUE(residual.spare_untouched());
  PetscBool equal = PETSC_FALSE;
  MatEqual(K_whole.mat(), K_view.mat(), &equal);
  EXPECT_TRUE(equal);
  double r_norm = 0;
  for (double v : r_whole) r_norm += v * v;
  EXPECT_GT(r_norm, 0);  // the state is not a trivial one

  ASSERT_FALSE(s->mesh.facet_tag_names.empty());
  for (const auto& [name, tag] : s->mesh.facet_tag_names) {
    const auto f_whole = boundary_force(space, materials, u, tag);
    const auto f_view = boundary_force(space, materials, state.view(), tag);
    EXPECT_NE(f_whole[0], 0.0) << name;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(f_view[c], f_whole[c]) << name;
  }
  const std::vector<double> stress = cell_cauchy_stress(space, materials, u);
  EXPECT_EQ(cell_cauchy_stress(space, materials, state.view()), stress);
  // Output of some cells (a process's VTU piece), in the order asked for.
  const std::vector<int> some = {17, 0, space.mesh().n_cells() - 1};
  const std::vector<double> some_stress = cell_cauchy_stress(space, materials, state.view(), &some);
  ASSERT_EQ(some_stress.size(), some.size() * 9);
  for (size_t k = 0; k < some.size(); ++k)
    for (int i = 0; i < 9; ++i) EXPECT_EQ(some_stress[k * 9 + i], stress[static_cast<size_t>(some[k]) * 9 + i]);
  // Nodal displacements (hierarchical edge coefficients turned into values) and pressures,
  // node by node through the view.
  const std::vector<double> nodal = space.nodal_values(u), pressure = space.nodal_pressure(u);
  double pressure_norm = 0;
  for (int n = 0; n < space.n_nodes(); ++n) {
    double value[3];
    space.nodal_value(state.view(), n, value);
    for (int k = 0; k < space.dim(); ++k) EXPECT_EQ(value[k], nodal[static_cast<size_t>(n) * space.dim() + k]);
    EXPECT_EQ(space.nodal_pressure(state.view(), n), pressure[n]);
    pressure_norm += std::abs(pressure[n]);
  }
  EXPECT_GT(pressure_norm, 0);
}

// A hierarchical P2 edge coefficient is the midpoint value minus the mean of the edge's
// vertex values: nodal_value adds the mean back, and the pressure at an edge node is the
// mean of its vertices' (P1 pressure).
TEST(AppView, NodalValuesOfHierarchicalCoefficients) {
  auto s = scene::build_scene(harness::builtin_scenes().at("mooney-rivlin-block"), "mooney-rivlin-block", ".", 0);
  const FieldSpace& space = *s->space;
  ASSERT_EQ(space.kind(), BasisKind::P2Hierarchical);
  ASSERT_TRUE(space.has_pressure());
  // The coefficients of the linear field g(x) = A x + b and the pressure p(x) = 2 + x_0.
  const auto g = [](const double* x, double* out) {
    out[0] = 0.1 * x[0] - 0.2 * x[1] + 0.05 * x[2] + 1;
    out[1] = 0.3 * x[2] - 2;
    out[2] = -0.4 * x[0] + 0.5;
  };
  std::vector<double> coefs(space.n_dofs(), 0.0);
  space.interpolate(g, coefs);
  for (int v = 0; v < space.n_vertices(); ++v)
    if (space.pressure_dof(v) >= 0) coefs[space.pressure_dof(v)] = 2 + space.mesh().vertex(v)[0];
  const test::ScatteredStorage state(coefs);
  int edge_nodes = 0;
  for (int n = 0; n < space.n_nodes(); ++n) {
    double x[3] = {0, 0, 0}, expected[3], value[3];
    space.node_position(n, x);
    g(x, expected);
    space.nodal_value(state.view(), n, value);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(value[k], expected[k], 1e-12) << "node " << n;
    EXPECT_NEAR(space.nodal_pressure(state.view(), n), 2 + x[0], 1e-12) << "node " << n;
    edge_nodes += space.is_vertex_node(n) ? 0 : 1;
  }
  EXPECT_GT(edge_nodes, 0);
}

}  // namespace
}  // namespace stiction::fem
