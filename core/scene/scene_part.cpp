#include "scene/scene_part.hpp"

#include "fem/mesh_partition.hpp"
#include "fem/part_numbering.hpp"

namespace stiction::scene {

std::unique_ptr<ScenePart> divide_scene(MPI_Comm comm, const Scene& scene, int levels) {
  // Every process evaluates the contact pairs whole, so each part holds their surfaces whole.
  std::vector<int> surface_tags;
  for (const auto* c : scene.problem.constraints)
    for (const auto& [role, tag] : c->surfaces()) surface_tags.push_back(tag);
  const fem::FieldSpace& whole = *scene.space;
  const fem::MeshPartition partition = fem::partition_cells(comm, scene.mesh);
  auto out = std::make_unique<ScenePart>();
  out->partitioner = partition.partitioner;
  out->part = mesh::local_part(scene.mesh, partition.cell_owner, partition.rank, surface_tags);
  for (int l = 0; l < levels; ++l) out->part = mesh::refine_parts(comm, out->part);
  const mesh::LocalMesh& part = out->part;
  // mesh::refine numbers the children of cell c consecutively from c * children.
  long long children = 1;
  for (int l = 0; l < levels; ++l) children *= scene.mesh.dim == 2 ? 4 : 8;

  // A vertex carries a pressure when a cell of a mixed law holds it (as the scene decides).
  std::vector<char> has_pressure;
  const auto ancestor = [&](int c) { return static_cast<size_t>(part.cell_ids[c] / children); };
  const auto ancestor_law = [&](int c) { return scene.problem.cell_material[ancestor(c)]; };
  if (whole.has_pressure()) {
    has_pressure.assign(part.mesh.n_vertices(), 0);
    for (int c = 0; c < part.mesh.n_cells(); ++c)
      if (ancestor_law(c)->mixed_bulk_modulus() > 0)
        for (int k = 0; k <= part.mesh.dim; ++k) has_pressure[part.mesh.cell(c)[k]] = 1;
  }
  out->space = std::make_unique<fem::FieldSpace>(part.mesh, whole.kind(), has_pressure);
  // The contact pairs over the part's space, their multipliers after its dofs, in order.
  std::vector<int> multiplier_vertices;
  for (const auto* c : scene.problem.constraints) {
    out->contacts.push_back(c->over(*out->space));
    const std::vector<int> v = out->contacts.back()->multiplier_vertices();
    multiplier_vertices.insert(multiplier_vertices.end(), v.begin(), v.end());
  }
  out->ownership = fem::own_part_unknowns(comm, part, *out->space, fem::number_part_space(comm, part, *out->space),
                                          multiplier_vertices);

  // The problem's conditions and loads are by facet tag and reference position, which the
  // part's facets and vertices keep; its laws are by cell.
  nonlinear::ElasticityProblem& p = out->problem;
  p = scene.problem;
  p.space = out->space.get();
  p.constraints.clear();
  for (const auto& c : out->contacts) p.constraints.push_back(c.get());
  p.cell_material.clear();
  for (int c = 0; c < part.mesh.n_cells(); ++c) {
    p.cell_material.push_back(ancestor_law(c));
    out->body_of_cell.push_back(scene.body_of_cell[ancestor(c)]);
  }
  return out;
}

void release_whole_mesh(Scene& scene) {
  scene.problem.space = nullptr;
  scene.problem.constraints.clear();
  std::vector<const materials::Material*>().swap(scene.problem.cell_material);
  scene.contacts.clear();
  scene.space.reset();
  std::vector<int>().swap(scene.body_of_cell);
  scene.mesh = mesh::Mesh{};
}

}  // namespace stiction::scene
