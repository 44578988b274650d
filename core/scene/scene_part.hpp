#pragma once
// A scene divided among MPI processes: each holds its part of the scene's mesh
// (mesh::LocalMesh: its cells and the layer around them), that part's own space, and the
// scene's problem over it (the same laws, boundary conditions and loads, addressed by the
// part's cells and facets), instead of the whole mesh on every process. The cells are split
// as fem::partition_cells splits the whole mesh, so a run on parts of the scene's own mesh
// takes the whole-mesh run's distributed Newton path.
//
// With levels > 0 the parts are then refined where they are (mesh::refine_parts), so that
// only the coarse mesh is ever whole: the result is the scene's mesh refined `levels` times
// and divided as its coarse cells were (a child's law is its coarse ancestor's). That is the
// scene's own finer level where its bodies are refined uniformly; a generator that re-meshes
// each level (curved Gmsh geometry, structured tubes) gives another mesh there.
//
// With contact, every process evaluates the contact pairs whole (as on the whole mesh): each
// part also holds the contact surfaces whole (the cells on them as ghosts), the pairs are
// rebuilt over the part's space and their multipliers are the part's unknowns after its
// dofs, owned by their slave vertex's owner. Refined in parts, a part holds the refined
// surfaces whole, and the pairs (made by the scene at level 0) are rebuilt over the finer
// part's space as the scene would make them at that level.
#include <memory>
#include <string>
#include <vector>

#include <mpi.h>

#include "fem/field_space.hpp"
#include "fem/part_ownership.hpp"
#include "mesh/local_mesh.hpp"
#include "nonlinear/multiplier_constraint.hpp"
#include "nonlinear/problem.hpp"
#include "scene/scene.hpp"

namespace stiction::scene {

struct ScenePart {
  mesh::LocalMesh part;
  std::unique_ptr<fem::FieldSpace> space;  // over part.mesh
  fem::PartOwnership ownership;            // of space's unknowns
  std::vector<std::unique_ptr<nonlinear::MultiplierConstraint>> contacts;  // the scene's pairs over space
  nonlinear::ElasticityProblem problem;    // over space; its laws are the scene's, its constraints `contacts`
  std::vector<int> body_of_cell;           // per part cell (Scene::body_of_cell)
  std::string partitioner;                 // what split the cells (empty on one process)

  ScenePart() = default;
  ScenePart(const ScenePart&) = delete;  // space points into part, problem into space
  ScenePart& operator=(const ScenePart&) = delete;
};

// Collective. The scene must outlive the result (its laws and load functions are shared).
std::unique_ptr<ScenePart> divide_scene(MPI_Comm comm, const Scene& scene, int levels = 0);

// Once a scene is divided its parts need nothing of its whole mesh: frees the mesh, the
// space, the contact pairs and the per-cell arrays. Its name, bodies, laws, loads, load
// steps and settings stay; its problem has no space, cells or constraints after it.
void release_whole_mesh(Scene& scene);

}  // namespace stiction::scene
