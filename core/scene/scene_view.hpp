#pragma once
// What a run's outputs (tables, VTU, run record) read of a scene: the whole scene, or one
// process's part of it (scene::divide_scene). The space, problem and bodies are the ones
// this process holds; the counts are of the whole mesh and space either way.
#include <cstdint>
#include <vector>

#include <mpi.h>

#include "fem/field_space.hpp"
#include "nonlinear/problem.hpp"
#include "scene/scene.hpp"
#include "scene/scene_part.hpp"

namespace stiction::scene {

struct SceneView {
  const Scene* scene = nullptr;  // name, bodies, settings (its mesh is the coarse one when refined in parts)
  int level = 0;                 // the level solved
  const fem::FieldSpace* space = nullptr;
  const nonlinear::ElasticityProblem* problem = nullptr;
  const std::vector<int>* body_of_cell = nullptr;  // per cell of space's mesh
  const std::vector<int>* vertex_ids = nullptr;  // in parts: each vertex's id in the whole mesh
  // The whole mesh's and space's sizes.
  std::int64_t n_vertices = 0, n_cells = 0, n_linear = 0, n_quadratic = 0, n_pressure = 0;

  SceneView(const Scene& whole);  // NOLINT(google-explicit-constructor): a scene is its own view
  std::int64_t n_dofs() const { return n_linear + n_quadratic + n_pressure; }
  int dim() const { return space->dim(); }
  // The whole mesh's id of vertex v of space's mesh.
  int whole_vertex(int v) const { return vertex_ids ? (*vertex_ids)[v] : v; }
};

// A process's part of `scene` refined to `level` (collective: the whole counts are summed
// over the processes' own cells and unknowns).
SceneView view_of_part(MPI_Comm comm, const Scene& scene, const ScenePart& part, int level);

}  // namespace stiction::scene
