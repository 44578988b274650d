#include "support/mesh_checks.hpp"

#include <gtest/gtest.h>

namespace stiction::test {

void expect_same_mesh(const mesh::Mesh& actual, const mesh::Mesh& expected) {
  EXPECT_EQ(actual.dim, expected.dim);
  EXPECT_EQ(actual.n_vertices(), expected.n_vertices());
  EXPECT_EQ(actual.n_cells(), expected.n_cells());
  EXPECT_EQ(actual.n_facets(), expected.n_facets());
  EXPECT_TRUE(actual.coords == expected.coords) << "vertex coordinates differ";
  EXPECT_TRUE(actual.cells == expected.cells) << "cell vertices differ";
  EXPECT_TRUE(actual.cell_tags == expected.cell_tags) << "cell tags differ";
  EXPECT_TRUE(actual.facets == expected.facets) << "facet vertices differ";
  EXPECT_TRUE(actual.facet_tags == expected.facet_tags) << "facet tags differ";
  EXPECT_EQ(actual.edge_midpoints.size(), expected.edge_midpoints.size());
  EXPECT_TRUE(actual.edge_midpoints == expected.edge_midpoints) << "curved edges differ";
  EXPECT_EQ(actual.cell_tag_names, expected.cell_tag_names);
  EXPECT_EQ(actual.facet_tag_names, expected.facet_tag_names);
}

void expect_same_part(const mesh::LocalMesh& actual, const mesh::LocalMesh& expected) {
  expect_same_mesh(actual.mesh, expected.mesh);
  EXPECT_EQ(actual.n_own_cells, expected.n_own_cells);
  EXPECT_TRUE(actual.vertex_ids == expected.vertex_ids) << "vertex ids differ";
  EXPECT_TRUE(actual.cell_ids == expected.cell_ids) << "cell ids differ";
  EXPECT_TRUE(actual.facet_ids == expected.facet_ids) << "facet ids differ";
  EXPECT_TRUE(actual.cell_owner == expected.cell_owner) << "cell owners differ";
  EXPECT_EQ(actual.n_global_vertices, expected.n_global_vertices);
  EXPECT_EQ(actual.n_global_cells, expected.n_global_cells);
  EXPECT_EQ(actual.n_global_facets, expected.n_global_facets);
}

}  // namespace stiction::test
