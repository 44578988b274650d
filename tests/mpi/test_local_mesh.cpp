// Run under `mpirun -n 2` with the other distributed tests. A mesh divided among the
// processes and refined in parts (mesh::refine_parts) is the refined whole mesh divided the
// same way: the same global ids, coordinates bit for bit, tagged facets and curved edges, on
// curved 2D and 3D scenes and on the block with strips (self-contact facets in its grooves),
// also when the parts hold the contact surfaces whole;
// a part's edges, nodes and pressure dofs get the whole mesh's numbers; and a layout over
// the part assembles the whole mesh's residual and tangent.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "builtin_scenes.hpp"
#include "fem/field_space.hpp"
#include "fem/ghosted_vector.hpp"
#include "fem/mesh_partition.hpp"
#include "fem/dof_layout.hpp"
#include "fem/elasticity_assembly.hpp"
#include "fem/part_numbering.hpp"
#include "fem/part_ownership.hpp"
#include "fem/stiffness_matrix.hpp"
#include "mesh/local_mesh.hpp"
#include "nonlinear/multiplier_constraint.hpp"
#include "scene/scene.hpp"
#include "support/mesh_checks.hpp"
#include "support/test_names.hpp"

namespace {

using namespace stiction;

struct RefinedScene {
  const char* name;
  int levels;
  bool hold_surfaces;  // the parts hold the contact surfaces whole
};
std::ostream& operator<<(std::ostream& os, const RefinedScene& s) {
  return os << s.name << " to level " << s.levels << (s.hold_surfaces ? ", holding the contact surfaces" : "");
}

// The facet tags of a scene's contact surfaces (slave and master of every pair).
std::vector<int> contact_surface_tags(const scene::Scene& s) {
  std::vector<int> tags;
  for (const auto* c : s.problem.constraints)
    for (const auto& [role, tag] : c->surfaces()) tags.push_back(tag);
  return tags;
}


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
  const auto [name, levels, hold_surfaces] = GetParam();
  const auto scene = scene::build_scene(harness::builtin_scenes().at(name), name, ".", 0);
  const std::vector<int> surfaces = hold_surfaces ? contact_surface_tags(*scene) : std::vector<int>{};
  EXPECT_EQ(surfaces.empty(), !hold_surfaces);
  mesh::Mesh whole = scene->mesh;
  const fem::MeshPartition partition = fem::partition_cells(PETSC_COMM_WORLD, whole);
  EXPECT_EQ(partition.size, 2) << "run under mpirun -n 2";
  std::vector<int> owner = partition.cell_owner;
  mesh::LocalMesh part = mesh::local_part(whole, owner, partition.rank, surfaces);
  const int children = whole.dim == 2 ? 4 : 8;
  for (int level = 1; level <= levels; ++level) {
    part = mesh::refine_parts(PETSC_COMM_WORLD, part);
    whole = mesh::refine(whole);
    std::vector<int> child_owner(static_cast<size_t>(whole.n_cells()));
    for (int c = 0; c < whole.n_cells(); ++c) child_owner[c] = owner[c / children];
    owner = std::move(child_owner);
    SCOPED_TRACE("level " + std::to_string(level));
    test::expect_same_part(part, mesh::local_part(whole, owner, partition.rank, surfaces));
    expect_whole_edge_numbering(part, whole);
  }
  // Without surfaces the part is its own cells and their vertex layer; holding them, it
  // also holds surface cells beyond the layer (as local_part makes it: checked above).
  const std::vector<int> layer = own_cells_and_vertex_layer(whole, owner, partition.rank);
  if (hold_surfaces) EXPECT_GT(part.cell_ids.size(), layer.size());
  else EXPECT_TRUE(part.cell_ids == layer);
  EXPECT_EQ(part.surface_tags, surfaces);
  // The parts are parts: each holds a ghost layer and less than the whole mesh, and their
  // own cells add up to it.
  EXPECT_GT(part.mesh.n_cells(), part.n_own_cells);
  EXPECT_LT(part.mesh.n_cells(), whole.n_cells());
  int own_total = 0;
  MPI_Allreduce(&part.n_own_cells, &own_total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_EQ(own_total, whole.n_cells());
}

// ironing-2d's indenter and the spheres have curved edges on their contact surfaces.
const RefinedScene kRefinedScenes[] = {{"ironing-2d", 2, false},      {"hertz-spheres-3d", 2, false},
                                       {"block-strips", 1, false},    {"ironing-2d", 2, true},
                                       {"hertz-spheres-3d", 2, true}, {"block-strips", 1, true}};

INSTANTIATE_TEST_SUITE_P(Scenes, RefinedInParts, ::testing::ValuesIn(kRefinedScenes), [](const auto& info) {
  return test::identifier(std::string(info.param.name) + (info.param.hold_surfaces ? "_holding_surfaces" : ""));
});

// A part's own space numbers its nodes (vertices, then P2 edges) and its pressure dofs as
// the whole mesh's space does, and owns and PETSc-numbers its unknowns as the whole mesh's
// layout does.
class NumberedInParts : public ::testing::TestWithParam<const char*> {};

// A scene's level-0 mesh divided between the processes, each with its part's own space (its
// pressure where the whole space has one) and that space's whole-space numbering; with
// hold_surfaces, each part holds the contact surfaces whole. Not to be moved: the space
// points into the part.
struct SceneInParts {
  std::unique_ptr<scene::Scene> scene;
  fem::MeshPartition partition;
  mesh::LocalMesh part;
  std::unique_ptr<fem::FieldSpace> space;
  fem::PartNumbering numbering;
  explicit SceneInParts(const char* name, bool hold_surfaces = false) {
    scene = scene::build_scene(harness::builtin_scenes().at(name), name, ".", 0);
    const fem::FieldSpace& whole = *scene->space;
    partition = fem::partition_cells(PETSC_COMM_WORLD, scene->mesh);
    part = mesh::local_part(scene->mesh, partition.cell_owner, partition.rank,
                            hold_surfaces ? contact_surface_tags(*scene) : std::vector<int>{});
    std::vector<char> has_pressure;
    for (int v = 0; whole.has_pressure() && v < part.mesh.n_vertices(); ++v)
      has_pressure.push_back(whole.pressure_dof(part.vertex_ids[v]) >= 0);
    space = std::make_unique<fem::FieldSpace>(part.mesh, whole.kind(), has_pressure);
    numbering = fem::number_part_space(PETSC_COMM_WORLD, part, *space);
  }
};

// A part's ownership against the whole mesh's layout: the same owned count and range, and
// for every unknown the part holds the same PETSc index and, where the part can tell, owner.
void expect_owned_as_the_layout(const fem::PartOwnership& o, const fem::DofLayout& layout, int rank) {
  EXPECT_EQ(o.n_owned, layout.n_owned());
  EXPECT_EQ(o.first_owned, layout.first_owned());
  int wrong_owner = 0, wrong_index = 0, not_owned = 0, unknown_owner = 0;
  for (size_t i = 0; i < o.app.size(); ++i) {
    wrong_owner += o.owner[i] >= 0 && o.owner[i] != layout.owner(o.app[i]);
    unknown_owner += o.owner[i] < 0 && layout.owns(o.app[i]);  // only another's can be unknown
    wrong_index += o.petsc[i] != layout.global(o.app[i]);
    not_owned += o.owner[i] != rank;
  }
  EXPECT_EQ(wrong_owner, 0) << "of " << o.app.size() << " unknowns";
  EXPECT_EQ(unknown_owner, 0) << "of " << o.app.size() << " unknowns";
  EXPECT_EQ(wrong_index, 0) << "of " << o.app.size() << " unknowns";
  EXPECT_GT(not_owned, 0);
}

// The part's nodes and pressures numbered as the whole space numbers them, its unknowns
// owned and PETSc-numbered as the whole mesh's layout does.
void expect_numbered_as_the_whole_space(const SceneInParts& s) {
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
  expect_owned_as_the_layout(fem::own_part_unknowns(PETSC_COMM_WORLD, part, space, n),
                             fem::DofLayout(PETSC_COMM_WORLD, whole, s.partition, {}), s.partition.rank);
}

TEST_P(NumberedInParts, AsTheWholeSpaceNumbersThem) { expect_numbered_as_the_whole_space(SceneInParts(GetParam())); }

// A part can hold the contact surfaces whole (every process evaluates contact whole): besides
// its own cells and their vertex layer, every cell with a facet on a contact surface as a
// ghost, each group ascending, and every facet of those surfaces; numbered and owned as the
// whole space and layout number them (the surfaces' vertices away from the own cells have no
// owner the part can tell).
class HoldingContactSurfaces : public ::testing::TestWithParam<const char*> {};

TEST_P(HoldingContactSurfaces, HoldThemWholeNumberedAsTheWholeSpace) {
  const SceneInParts s(GetParam(), true);
  const mesh::Mesh& whole = s.scene->mesh;
  const std::vector<int> tags = contact_surface_tags(*s.scene);
  EXPECT_FALSE(tags.empty());
  const auto on_surface = [&](int tag) { return std::find(tags.begin(), tags.end(), tag) != tags.end(); };
  std::vector<std::array<int, 3>> surface_keys;
  std::vector<int> surface_facets;
  for (int f = 0; f < whole.n_facets(); ++f)
    if (on_surface(whole.facet_tags[f])) {
      surface_keys.push_back(mesh::facet_key(whole.facet(f), whole.dim));
      surface_facets.push_back(f);
    }
  std::sort(surface_keys.begin(), surface_keys.end());
  std::vector<int> expected = own_cells_and_vertex_layer(whole, s.partition.cell_owner, s.partition.rank);
  const size_t n_own = static_cast<size_t>(s.part.n_own_cells);
  int surface_only = 0;  // surface cells beyond the vertex layer
  for (int c = 0; c < whole.n_cells(); ++c) {
    if (s.partition.cell_owner[c] == s.partition.rank ||
        std::find(expected.begin() + static_cast<long>(n_own), expected.end(), c) != expected.end())
      continue;
    for (const auto& key : mesh::cell_facet_keys(whole.cell(c), whole.dim))
      if (std::binary_search(surface_keys.begin(), surface_keys.end(), key)) {
        expected.push_back(c);
        ++surface_only;
        break;
      }
  }
  std::sort(expected.begin() + static_cast<long>(n_own), expected.end());
  EXPECT_EQ(s.part.cell_ids, expected);
  EXPECT_GT(surface_only, 0) << "the surfaces lie within the vertex layer: nothing is tested";
  std::vector<int> held_surface_facets;
  for (int f = 0; f < s.part.mesh.n_facets(); ++f)
    if (on_surface(s.part.mesh.facet_tags[f])) held_surface_facets.push_back(s.part.facet_ids[f]);
  EXPECT_EQ(held_surface_facets, surface_facets);
  expect_numbered_as_the_whole_space(s);
}

// With the surfaces whole, a part holds every contact multiplier (after its space's dofs),
// owned by its slave vertex's owner and PETSc-numbered as the whole mesh's layout numbers
// the multipliers it appends; the layout over the part has the whole system's size.
TEST_P(HoldingContactSurfaces, OwnAndNumberTheMultipliersAsTheWholeLayout) {
  const SceneInParts s(GetParam(), true);
  std::vector<int> whole_vertices, part_vertices;  // every constraint's multiplier vertices, in order
  for (const auto* c : s.scene->problem.constraints) {
    const std::vector<int> v = c->multiplier_vertices();
    whole_vertices.insert(whole_vertices.end(), v.begin(), v.end());
  }
  EXPECT_FALSE(whole_vertices.empty());
  for (int v : whole_vertices) {
    const auto at = std::lower_bound(s.part.vertex_ids.begin(), s.part.vertex_ids.end(), v);
    part_vertices.push_back(at != s.part.vertex_ids.end() && *at == v ? static_cast<int>(at - s.part.vertex_ids.begin())
                                                                        : -1);
  }
  EXPECT_EQ(std::count(part_vertices.begin(), part_vertices.end(), -1), 0) << "a slave vertex is not in the part";
  std::replace(part_vertices.begin(), part_vertices.end(), -1, 0);  // no early return before the collectives
  fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, s.part, *s.space, s.numbering, part_vertices);
  const fem::DofLayout whole(PETSC_COMM_WORLD, *s.scene->space, s.partition, whole_vertices);
  EXPECT_EQ(o.app.size(), static_cast<size_t>(s.space->n_dofs()) + whole_vertices.size());
  int owned_multipliers = 0;
  for (size_t k = 0; k < whole_vertices.size(); ++k)
    owned_multipliers += o.owner[static_cast<size_t>(s.space->n_dofs()) + k] == s.partition.rank;
  int owned_anywhere = 0;  // each multiplier has one owner
  MPI_Allreduce(&owned_multipliers, &owned_anywhere, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_EQ(owned_anywhere, static_cast<int>(whole_vertices.size()));
  expect_owned_as_the_layout(o, whole, s.partition.rank);
  const fem::DofLayout over_part(PETSC_COMM_WORLD, s.part, *s.space, std::move(o));
  EXPECT_EQ(over_part.n_total(), whole.n_total());
  EXPECT_EQ(over_part.n_owned(), whole.n_owned());
}


// A state of small random displacements (and pressures) of the whole space, the same on
// every process.
std::vector<double> random_whole_state(const fem::FieldSpace& whole) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> amplitude(-0.05, 0.05);
  std::vector<double> u(static_cast<size_t>(whole.n_dofs()));
  for (double& x : u) x = amplitude(gen);
  return u;
}

std::vector<const materials::Material*> part_materials(const SceneInParts& s) {
  std::vector<const materials::Material*> out;
  for (int id : s.part.cell_ids) out.push_back(s.scene->problem.cell_material[id]);
  return out;
}

// The whole mesh's internal forces at a whole state.
std::vector<double> whole_residual(const SceneInParts& s, const std::vector<double>& u) {
  std::vector<double> r(u.size(), 0.0);
  EXPECT_EQ(fem::assemble_internal(*s.scene->space, s.scene->problem.cell_material, u, r, nullptr).inverted_cell, -1);
  return r;
}

// A part carries what the assembly needs: the internal forces of its cells on its own space
// (curved edges and pressures included), from the whole state's values at its unknowns, are
// the whole residual's values at every unknown it owns (to round-off: the cells are summed
// in another order).
TEST_P(NumberedInParts, AssembleTheWholeResidualAtTheirOwnedUnknowns) {
  const SceneInParts s(GetParam());
  const fem::FieldSpace& whole = *s.scene->space;
  const std::vector<double> u_whole = random_whole_state(whole);
  const std::vector<double> r_whole = whole_residual(s, u_whole);

  const fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, s.part, *s.space, s.numbering);
  std::vector<double> u(o.app.size()), r(o.app.size(), 0.0);
  for (size_t i = 0; i < u.size(); ++i) u[i] = u_whole[o.app[i]];
  EXPECT_EQ(fem::assemble_internal(*s.space, part_materials(s), u, r, nullptr).inverted_cell, -1);

  double scale = 0;
  for (double x : r_whole) scale = std::max(scale, std::abs(x));
  int owned = 0;
  double worst = 0;
  for (size_t i = 0; i < r.size(); ++i)
    if (o.owner[i] == s.partition.rank) worst = std::max(worst, std::abs(r[i] - r_whole[o.app[i]])), ++owned;
  EXPECT_LT(worst, 1e-12 * scale);
  EXPECT_EQ(owned, o.n_owned);
  EXPECT_GT(scale, 0);
}

// The tangent assembled on the parts, each process its owned rows from its part's cells
// through a layout over the part, is the one the whole mesh's distributed assembly gives:
// the same PETSc numbering, the same nonzero pattern, values to round-off.
TEST_P(NumberedInParts, AssembleTheWholeTangent) {
  const SceneInParts s(GetParam());
  const fem::FieldSpace& whole = *s.scene->space;
  const std::vector<double> u_whole = random_whole_state(whole);
  const fem::DofLayout whole_layout(PETSC_COMM_WORLD, whole, s.partition, {});
  fem::StiffnessMatrix whole_tangent(whole_layout, whole);
  whole_tangent.begin_assembly();
  std::vector<double> no_residual;
  const auto whole_status = fem::assemble_internal(whole, s.scene->problem.cell_material, u_whole, no_residual,
                                                   &whole_tangent, &whole_layout.row_cells());
  whole_tangent.end_assembly();

  const fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, s.part, *s.space, s.numbering);
  const fem::DofLayout layout(PETSC_COMM_WORLD, s.part, *s.space, o);
  EXPECT_TRUE(layout.over_part());
  std::vector<double> u(o.app.size());
  for (size_t i = 0; i < u.size(); ++i) u[i] = u_whole[o.app[i]];
  fem::StiffnessMatrix tangent(layout, *s.space);
  tangent.begin_assembly();
  const auto status = fem::assemble_internal(*s.space, part_materials(s), u, no_residual, &tangent, &layout.row_cells());
  tangent.end_assembly();
  EXPECT_EQ(whole_status.inverted_cell, -1);
  EXPECT_EQ(status.inverted_cell, -1);

  MatInfo whole_info, info;
  MatGetInfo(whole_tangent.mat(), MAT_GLOBAL_SUM, &whole_info);
  MatGetInfo(tangent.mat(), MAT_GLOBAL_SUM, &info);
  EXPECT_EQ(info.nz_used, whole_info.nz_used);
  PetscReal scale = 0, difference = 0;
  MatNorm(whole_tangent.mat(), NORM_INFINITY, &scale);
  MatAXPY(tangent.mat(), -1.0, whole_tangent.mat(), SAME_NONZERO_PATTERN);
  MatNorm(tangent.mat(), NORM_INFINITY, &difference);
  EXPECT_LT(difference, 1e-12 * scale);
  EXPECT_GT(scale, 0);
}

// A layout over a part moves vectors and field blocks between PETSc's numbering and the app
// order as the whole mesh's layout does, with the indices of unknowns the part does not
// hold asked of their owners.
TEST_P(NumberedInParts, LayOutVectorsAndFieldBlocksAsTheWholeMesh) {
  const SceneInParts s(GetParam());
  const fem::FieldSpace& whole = *s.scene->space;
  const fem::DofLayout whole_layout(PETSC_COMM_WORLD, whole, s.partition, {});
  const fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, s.part, *s.space, s.numbering);
  const fem::DofLayout layout(PETSC_COMM_WORLD, s.part, *s.space, o);
  EXPECT_EQ(layout.n_total(), whole_layout.n_total());
  EXPECT_EQ(layout.n_owned(), whole_layout.n_owned());
  EXPECT_EQ(layout.first_owned(), whole_layout.first_owned());
  EXPECT_EQ(layout.owned_cells().size(), static_cast<size_t>(s.part.n_own_cells));
  int wrong_owned = 0;
  for (PetscInt j = 0; j < layout.n_owned(); ++j) wrong_owned += layout.app(layout.local_of_owned(j)) != whole_layout.local_of_owned(j);
  EXPECT_EQ(wrong_owned, 0);

  // Every field block (the displacement's vertex and edge blocks, the pressures where
  // present), as the part's space and the whole space give its range: the same owned PETSc
  // indices, and each held unknown's number within the block.
  using Blocks = std::vector<std::pair<int, int>>;
  Blocks blocks = {s.space->linear_block(), s.space->quadratic_block()};
  Blocks whole_blocks = {whole.linear_block(), whole.quadratic_block()};
  if (whole.has_pressure()) blocks.push_back(s.space->pressure_block()), whole_blocks.push_back(whole.pressure_block());
  for (size_t b = 0; b < blocks.size(); ++b) {
    const auto [first, last] = blocks[b];
    const auto [whole_first, whole_last] = whole_blocks[b];
    EXPECT_EQ(layout.owned_indices(first, last), whole_layout.owned_indices(whole_first, whole_last)) << b;
    const std::vector<PetscInt> number = layout.block_numbering(first, last);
    const std::vector<PetscInt> whole_number = whole_layout.block_numbering(whole_first, whole_last);
    int wrong = 0;
    for (PetscInt l = first; l < last; ++l) wrong += number[l - first] != whole_number[layout.app(l) - whole_first];
    EXPECT_EQ(wrong, 0) << "block " << b << " of " << last - first;
  }

  // Whole app-ordered values into a distributed vector and back, through each layout.
  const std::vector<double> values = random_whole_state(whole);
  PetscVec v(layout.create_vector()), v_whole(whole_layout.create_vector());
  layout.scatter(values, v);
  whole_layout.scatter(values, v_whole);
  PetscBool same = PETSC_FALSE;
  VecEqual(v, v_whole, &same);
  EXPECT_TRUE(same);
  std::vector<double> back, on_root;
  layout.gather(v, back);
  EXPECT_EQ(back, values);
  VecZeroEntries(v);
  layout.scatter_from_root(s.partition.rank == 0 ? values : std::vector<double>{}, v);
  VecEqual(v, v_whole, &same);
  EXPECT_TRUE(same);
  layout.gather_on_root(v, on_root);
  EXPECT_EQ(on_root, s.partition.rank == 0 ? values : std::vector<double>{});
}

// Over a part, the Newton state is held as the part's owned unknowns and ghosts, addressed
// by the part's own dof numbers: ghosts take their owners' values, and the internal forces
// assembled through the ghosted state over the part's row cells gather into the whole
// residual.
TEST_P(NumberedInParts, HoldTheStateAsGhostedVectors) {
  const SceneInParts s(GetParam());
  const fem::FieldSpace& whole = *s.scene->space;
  const std::vector<double> u_whole = random_whole_state(whole);
  const std::vector<double> r_whole = whole_residual(s, u_whole);

  const fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, s.part, *s.space, s.numbering);
  const fem::DofLayout layout(PETSC_COMM_WORLD, s.part, *s.space, o);
  auto pattern = std::make_shared<const fem::GhostPattern>(layout, fem::unknowns_of_cells(*s.space, layout.row_cells()));
  EXPECT_GT(pattern->n_ghosts(), 0);
  EXPECT_EQ(pattern->storage_of_local().size(), o.app.size());  // the part's size, not the whole system's

  fem::GhostedVector u(pattern);
  fem::ResidualView uv = u.view();
  for (PetscInt l = 0; l < layout.n_held(); ++l)
    if (layout.owns(l)) uv[l] = u_whole[layout.app(l)];
  u.update_ghosts();
  int wrong = 0, stored = 0;
  for (PetscInt l = 0; l < layout.n_held(); ++l)
    if (pattern->holds(l)) wrong += uv[l] != u_whole[layout.app(l)], ++stored;
  EXPECT_EQ(wrong, 0) << "of " << stored;
  EXPECT_EQ(stored, pattern->n_stored());

  fem::GhostedVector r(pattern);
  EXPECT_EQ(fem::assemble_internal(*s.space, part_materials(s), u.view(), r.view(), nullptr, &layout.row_cells()).inverted_cell, -1);
  const std::vector<double> r_gathered = r.whole();
  ASSERT_EQ(r_gathered.size(), r_whole.size());
  double scale = 0, worst = 0;
  for (size_t a = 0; a < r_whole.size(); ++a)
    scale = std::max(scale, std::abs(r_whole[a])), worst = std::max(worst, std::abs(r_gathered[a] - r_whole[a]));
  EXPECT_LT(worst, 1e-12 * scale);
  EXPECT_GT(scale, 0);
}

const char* const kNumberedScenes[] = {"mooney-rivlin-block", "block-strips-mr", "hertz-spheres-3d"};

INSTANTIATE_TEST_SUITE_P(Scenes, NumberedInParts, ::testing::ValuesIn(kNumberedScenes),
                         [](const auto& info) { return test::identifier(info.param); });

// Jacobian entries summed by (row, column), the indices taken through `app`.
std::map<std::pair<PetscInt, PetscInt>, double> entries_by_app(const nonlinear::SparseEntries& e,
                                                               const std::function<PetscInt(PetscInt)>& app) {
  std::map<std::pair<PetscInt, PetscInt>, double> out;
  for (size_t k = 0; k < e.size(); ++k) out[{app(e.rows[k]), app(e.cols[k])}] += e.values[k];
  return out;
}

// With the surfaces whole, a contact pair rebuilt over the part's space
// (MultiplierConstraint::over) is the whole mesh's pair: the same multiplier nodes in the same
// order and, at a state of small random displacements and multipliers, the same rows r_c,
// constraint forces at every unknown (the part holds all of them), Jacobian entries (in app
// numbering) and state updates, to round-off. Every process evaluates the whole pair here.
TEST_P(HoldingContactSurfaces, EvaluateTheirPairsAsTheWholeMesh) {
  const SceneInParts s(GetParam(), true);
  const fem::FieldSpace& whole = *s.scene->space;
  const fem::FieldSpace& space = *s.space;
  const fem::PartOwnership o = fem::own_part_unknowns(PETSC_COMM_WORLD, s.part, space, s.numbering);
  const std::vector<double> u_whole = random_whole_state(whole);
  std::vector<double> u(o.app.size());
  for (size_t i = 0; i < u.size(); ++i) u[i] = u_whole[o.app[i]];
  const double t = 1.0;  // block-strips: the ground has risen into the strips
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> traction(-0.2, 0.2);
  int pairs = 0, constrained = 0;
  for (const auto* c : s.scene->problem.constraints) {
    SCOPED_TRACE(c->name());
    const auto a = c->over(whole), b = c->over(space);
    std::vector<int> vertices = b->multiplier_vertices();
    for (int& v : vertices) v = s.part.vertex_ids[v];
    EXPECT_EQ(vertices, a->multiplier_vertices());
    const int m = a->n_multipliers();
    if (b->n_multipliers() != m) continue;  // failed above; nothing below is collective
    ++pairs;
    std::vector<double> lambda(m), dlambda(m);
    for (double& x : lambda) x = traction(gen);
    for (double& x : dlambda) x = traction(gen);
    const PetscInt n_whole = whole.n_dofs(), n_part = space.n_dofs();
    const auto part_app = [&](PetscInt i) { return i < n_part ? o.app[i] : n_whole + (i - n_part); };
    a->begin_increment(0.0, u_whole);
    b->begin_increment(0.0, u);
    for (int round = 0; round < 2; ++round) {  // the first states, then those the update sets
      std::vector<double> ru_whole(u_whole.size(), 0.0), ru(u.size(), 0.0), rc_whole(m), rc(m);
      nonlinear::SparseEntries j_whole, j;
      a->evaluate(t, u_whole, lambda.data(), ru_whole, rc_whole.data(), &j_whole, n_whole);
      b->evaluate(t, u, lambda.data(), ru, rc.data(), &j, n_part);
      double scale = 0, worst = 0, held = 0, all = 0;
      for (double x : ru_whole) scale = std::max(scale, std::abs(x)), all += std::abs(x);
      for (size_t i = 0; i < ru.size(); ++i) worst = std::max(worst, std::abs(ru[i] - ru_whole[o.app[i]])), held += std::abs(ru[i]);
      EXPECT_GT(scale, 0);
      EXPECT_LE(worst, 1e-12 * scale) << "round " << round;
      EXPECT_NEAR(held, all, 1e-10 * all) << "a force lands on an unknown the part does not hold";
      for (int k = 0; k < m; ++k) EXPECT_NEAR(rc[k], rc_whole[k], 1e-12 * (1 + std::abs(rc_whole[k]))) << "row " << k;
      const auto ej = entries_by_app(j, part_app);
      const auto ej_whole = entries_by_app(j_whole, [](PetscInt i) { return i; });
      EXPECT_EQ(ej.size(), ej_whole.size()) << "round " << round;
      double jscale = 0, jworst = 0;
      for (const auto& [key, v] : ej_whole) {
        jscale = std::max(jscale, std::abs(v));
        const auto it = ej.find(key);
        jworst = std::max(jworst, std::abs(v - (it == ej.end() ? 0.0 : it->second)));
      }
      EXPECT_LE(jworst, 1e-12 * jscale) << "round " << round;
      if (round == 0) {
        EXPECT_EQ(b->update_states(t, u, lambda.data(), dlambda.data()),
                  a->update_states(t, u_whole, lambda.data(), dlambda.data()));
        EXPECT_EQ(b->states(), a->states());
        const auto states = a->states();
        constrained += static_cast<int>(std::count_if(states.begin(), states.end(),
                                                      [](char x) { return x != nonlinear::MultiplierConstraint::kFreeState; }));
      }
    }
  }
  EXPECT_GT(pairs, 0);
  EXPECT_GT(constrained, 0) << "no node entered contact: the constrained rows are not compared";
}

INSTANTIATE_TEST_SUITE_P(Scenes, HoldingContactSurfaces, ::testing::Values("block-strips", "hertz-spheres-3d"),
                         [](const auto& info) { return test::identifier(info.param); });

// The curved scenes' meshes are curved, so the test compares curved edges too.
TEST(RefinedInPartsScenes, CurvedOnesAreCurved) {
  for (const char* name : {"ironing-2d", "hertz-spheres-3d"}) {
    const auto scene = scene::build_scene(harness::builtin_scenes().at(name), name, ".", 0);
    EXPECT_TRUE(scene->mesh.is_curved()) << name;
  }
}

}  // namespace
