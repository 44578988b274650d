// Run under `mpirun -n 2` with the other distributed tests. A mesh divided among the
// processes and refined in parts (mesh::refine_parts) is the refined whole mesh divided the
// same way: the same global ids, coordinates bit for bit, tagged facets and curved edges, on
// curved 2D and 3D scenes and on the block with strips (self-contact facets in its grooves);
// and a part's edges, nodes and pressure dofs get the whole mesh's numbers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <ostream>
#include <string>
#include <vector>

#include "builtin_scenes.hpp"
#include "fem/field_space.hpp"
#include "fem/mesh_partition.hpp"
#include "fem/dof_layout.hpp"
#include "fem/elasticity_assembly.hpp"
#include "fem/part_numbering.hpp"
#include "fem/part_ownership.hpp"
#include "mesh/local_mesh.hpp"
#include "scene/scene.hpp"
#include "support/mesh_checks.hpp"
#include "support/test_names.hpp"

namespace {

using namespace stiction;

struct RefinedScene {
  const char* name;
  int levels;
};
std::ostream& operator<<(std::ostream& os, const RefinedScene& s) { return os << s.name << " to level " << s.levels; }

// Every edge of the part, ghosts' included, has the id the whole mesh's edge list gives it.
void expect_whole_edge_numbering(const mesh::LocalMesh& part, const mesh::Mesh& whole) {
  const mesh::EdgeTopology local = mesh::build_edges(part.mesh), all = mesh::build_edges(whole);
  const mesh::GlobalEdges ids = mesh::global_edge_ids(PETSC_COMM_WORLD, part, local);
  EXPECT_EQ(ids.n_global, all.n_edges());
  ASSERT_EQ(ids.id.size(), local.edges.size());
  int wrong = 0;
  for (size_t e = 0; e < local.edges.size(); ++e)
    wrong += ids.id[e] != all.find(part.vertex_ids[local.edges[e][0]], part.vertex_ids[local.edges[e][1]]);
  EXPECT_EQ(wrong, 0) << "of " << local.edges.size() << " edges";
  // Some edges lie away from the own cells (their low end's star is not in the part): those
  // are numbered by the ghost cell's owner, and the check above covers them.
  std::vector<char> own_vertex(static_cast<size_t>(part.mesh.n_vertices()), 0);
  for (int c = 0; c < part.n_own_cells; ++c)
    for (int k = 0; k < part.mesh.vertices_per_cell(); ++k) own_vertex[part.mesh.cell(c)[k]] = 1;
  int away = 0;
  for (const auto& edge : local.edges) away += !own_vertex[edge[0]];
  EXPECT_GT(away, 0);
}

// The part's cells, straight from the whole mesh: the own ones, then every other cell with a
// vertex of an own cell, each group ascending.
std::vector<int> own_cells_and_vertex_layer(const mesh::Mesh& whole, const std::vector<int>& owner, int rank) {
  std::vector<char> own_vertex(static_cast<size_t>(whole.n_vertices()), 0);
  std::vector<int> cells;
  for (int c = 0; c < whole.n_cells(); ++c)
    if (owner[c] == rank) {
      cells.push_back(c);
      for (int k = 0; k < whole.vertices_per_cell(); ++k) own_vertex[whole.cell(c)[k]] = 1;
    }
  for (int c = 0; c < whole.n_cells(); ++c)
    if (owner[c] != rank && std::any_of(whole.cell(c), whole.cell(c) + whole.vertices_per_cell(), [&](int v) { return own_vertex[v]; }))
      cells.push_back(c);
  return cells;
}

class RefinedInParts : public ::testing::TestWithParam<RefinedScene> {};

// No ASSERT before a collective: a process that returned early would leave the other in it.
TEST_P(RefinedInParts, IsTheRefinedWholeMeshDivided) {
  const auto [name, levels] = GetParam();
  const auto scene = scene::build_scene(harness::builtin_scenes().at(name), name, ".", 0);
  mesh::Mesh whole = scene->mesh;
  const fem::MeshPartition partition = fem::partition_cells(PETSC_COMM_WORLD, whole);
  EXPECT_EQ(partition.size, 2) << "run under mpirun -n 2";
  std::vector<int> owner = partition.cell_owner;
  mesh::LocalMesh part = mesh::local_part(whole, owner, partition.rank);
  const int children = whole.dim == 2 ? 4 : 8;
  for (int level = 1; level <= levels; ++level) {
    part = mesh::refine_parts(PETSC_COMM_WORLD, part);
    whole = mesh::refine(whole);
    std::vector<int> child_owner(static_cast<size_t>(whole.n_cells()));
    for (int c = 0; c < whole.n_cells(); ++c) child_owner[c] = owner[c / children];
    owner = std::move(child_owner);
    SCOPED_TRACE("level " + std::to_string(level));
    test::expect_same_part(part, mesh::local_part(whole, owner, partition.rank));
    expect_whole_edge_numbering(part, whole);
  }
  EXPECT_TRUE(part.cell_ids == own_cells_and_vertex_layer(whole, owner, partition.rank));
  // The parts are parts: each holds a ghost layer and less than the whole mesh, and their
  // own cells add up to it.
  EXPECT_GT(part.mesh.n_cells(), part.n_own_cells);
  EXPECT_LT(part.mesh.n_cells(), whole.n_cells());
  int own_total = 0;
  MPI_Allreduce(&part.n_own_cells, &own_total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_EQ(own_total, whole.n_cells());
}

const RefinedScene kRefinedScenes[] = {{"ironing-2d", 2}, {"hertz-spheres-3d", 2}, {"block-strips", 1}};

INSTANTIATE_TEST_SUITE_P(Scenes, RefinedInParts, ::testing::ValuesIn(kRefinedScenes),
                         [](const auto& info) { return test::identifier(info.param.name); });

// A part's own space numbers its nodes (vertices, then P2 edges) and its pressure dofs as
// the whole mesh's space does, and owns and PETSc-numbers its unknowns as the whole mesh's
// layout does.
class NumberedInParts : public ::testing::TestWithParam<const char*> {};

// A scene's level-0 mesh divided between the processes, each with its part's own space (its
// pressure where the whole space has one) and that space's whole-space numbering. Not to be
// moved: the space points into the part.
struct SceneInParts {
  std::unique_ptr<scene::Scene> scene;
  fem::MeshPartition partition;
  mesh::LocalMesh part;
  std::unique_ptr<fem::FieldSpace> space;
  fem::PartNumbering numbering;
  explicit SceneInParts(const char* name) {
    scene = scene::build_scene(harness::builtin_scenes().at(name), name, ".", 0);
    const fem::FieldSpace& whole = *scene->space;
    partition = fem::partition_cells(PETSC_COMM_WORLD, scene->mesh);
    part = mesh::local_part(scene->mesh, partition.cell_owner, partition.rank);
    std::vector<char> has_pressure;
    for (int v = 0; whole.has_pressure() && v < part.mesh.n_vertices(); ++v)
      has_pressure.push_back(whole.pressure_dof(part.vertex_ids[v]) >= 0);
    space = std::make_unique<fem::FieldSpace>(part.mesh, whole.kind(), has_pressure);
    numbering = fem::number_part_space(PETSC_COMM_WORLD, part, *space);
  }
};

TEST_P(NumberedInParts, AsTheWholeSpaceNumbersThem) {
  const SceneInParts s(GetParam());
  const fem::FieldSpace& whole = *s.scene->space;
  const fem::FieldSpace& space = *s.space;
  const mesh::LocalMesh& part = s.part;
  const fem::PartNumbering& n = s.numbering;

  EXPECT_EQ(n.n_global_nodes, whole.n_nodes());
  EXPECT_EQ(n.n_global_pressures, whole.n_pressure_dofs());
  ASSERT_EQ(static_cast<int>(n.node.size()), space.n_nodes());
  int wrong_nodes = 0, edge_nodes = 0;
  for (int node = 0; node < space.n_nodes(); ++node) {
    if (space.is_vertex_node(node)) {
      wrong_nodes += n.node[node] != part.vertex_ids[node];
      continue;
    }
    const auto& edge = space.edges().edges[node - space.n_vertices()];
    const int e = whole.edges().find(part.vertex_ids[edge[0]], part.vertex_ids[edge[1]]);
    wrong_nodes += n.node[node] != whole.n_vertices() + e;
    ++edge_nodes;
  }
  EXPECT_EQ(wrong_nodes, 0) << "of " << space.n_nodes() << " nodes";
  EXPECT_GT(edge_nodes, 0);  // a P2 space
  int wrong_pressures = 0, pressures = 0;
  for (int v = 0; v < space.n_vertices(); ++v) {
    if (space.pressure_dof(v) < 0) continue;
    wrong_pressures += n.pressure[v] != whole.pressure_dof(part.vertex_ids[v]) - whole.n_displacement_dofs();
    ++pressures;
  }
  EXPECT_EQ(wrong_pressures, 0) << "of " << pressures << " pressures";
  EXPECT_EQ(pressures > 0, whole.has_pressure());

  // Ownership and PETSc's numbering as the whole mesh's layout gives them; the unknowns the
  // part holds but does not own get theirs from their owners.
  const fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, part, space, n);
  const fem::DofLayout layout(PETSC_COMM_WORLD, whole, s.partition, {});
  EXPECT_EQ(o.n_owned, layout.n_owned());
  EXPECT_EQ(o.first_owned, layout.first_owned());
  int wrong_owner = 0, wrong_index = 0, not_owned = 0;
  for (size_t i = 0; i < o.app.size(); ++i) {
    wrong_owner += static_cast<bool>(o.owned[i]) != layout.owns(o.app[i]);
    wrong_index += o.petsc[i] != layout.global(o.app[i]);
    not_owned += !o.owned[i];
  }
  EXPECT_EQ(wrong_owner, 0) << "of " << o.app.size() << " unknowns";
  EXPECT_EQ(wrong_index, 0) << "of " << o.app.size() << " unknowns";
  EXPECT_GT(not_owned, 0);
}

// A part carries what the assembly needs: the internal forces of its cells on its own space
// (curved edges and pressures included), from the whole state's values at its unknowns, are
// the whole residual's values at every unknown it owns (to round-off: the cells are summed
// in another order).
TEST_P(NumberedInParts, AssembleTheWholeResidualAtTheirOwnedUnknowns) {
  const SceneInParts s(GetParam());
  const fem::FieldSpace& whole = *s.scene->space;
  const auto& materials = s.scene->problem.cell_material;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> amplitude(-0.05, 0.05);
  std::vector<double> u_whole(static_cast<size_t>(whole.n_dofs()));
  for (double& x : u_whole) x = amplitude(gen);
  std::vector<double> r_whole(u_whole.size(), 0.0);
  EXPECT_EQ(fem::assemble_internal(whole, materials, u_whole, r_whole, nullptr).inverted_cell, -1);

  const fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, s.part, *s.space, s.numbering);
  std::vector<const materials::Material*> part_materials;
  for (int id : s.part.cell_ids) part_materials.push_back(materials[id]);
  std::vector<double> u(o.app.size()), r(o.app.size(), 0.0);
  for (size_t i = 0; i < u.size(); ++i) u[i] = u_whole[o.app[i]];
  EXPECT_EQ(fem::assemble_internal(*s.space, part_materials, u, r, nullptr).inverted_cell, -1);

  double scale = 0;
  for (double x : r_whole) scale = std::max(scale, std::abs(x));
  int owned = 0;
  double worst = 0;
  for (size_t i = 0; i < r.size(); ++i)
    if (o.owned[i]) worst = std::max(worst, std::abs(r[i] - r_whole[o.app[i]])), ++owned;
  EXPECT_LT(worst, 1e-12 * scale);
  EXPECT_EQ(owned, o.n_owned);
  EXPECT_GT(scale, 0);
}

const char* const kNumberedScenes[] = {"mooney-rivlin-block", "block-strips-mr", "hertz-spheres-3d"};

INSTANTIATE_TEST_SUITE_P(Scenes, NumberedInParts, ::testing::ValuesIn(kNumberedScenes),
                         [](const auto& info) { return test::identifier(info.param); });

// The curved scenes' meshes are curved, so the test compares curved edges too.
TEST(RefinedInPartsScenes, CurvedOnesAreCurved) {
  for (const char* name : {"ironing-2d", "hertz-spheres-3d"}) {
    const auto scene = scene::build_scene(harness::builtin_scenes().at(name), name, ".", 0);
    EXPECT_TRUE(scene->mesh.is_curved()) << name;
  }
}

}  // namespace
