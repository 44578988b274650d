#include "scene/scene_view.hpp"

#include <array>

namespace stiction::scene {

SceneView::SceneView(const Scene& whole)
    : scene(&whole),
      level(whole.level),
      space(whole.space.get()),
      problem(&whole.problem),
      body_of_cell(&whole.body_of_cell),
      n_vertices(whole.mesh.n_vertices()),
      n_cells(whole.mesh.n_cells()),
      n_linear(whole.space->linear_block().second - whole.space->linear_block().first),
      n_quadratic(whole.space->quadratic_block().second - whole.space->quadratic_block().first),
      n_pressure(whole.space->n_pressure_dofs()) {}

SceneView view_of_part(MPI_Comm comm, const Scene& scene, const ScenePart& part, int level) {
  SceneView v(scene);
  v.level = level;
  v.space = part.space.get();
  v.problem = &part.problem;
  v.body_of_cell = &part.body_of_cell;
  v.vertex_ids = &part.part.vertex_ids;
  v.n_vertices = part.part.n_global_vertices;
  v.n_cells = part.part.n_global_cells;
  // The unknowns this process owns in each block (the part's dofs keep the whole space's
  // block order: vertices, edge nodes, pressures), summed over the processes.
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const auto owned_in = [&](std::pair<int, int> block) {
    std::int64_t n = 0;
    for (int d = block.first; d < block.second; ++d) n += part.ownership.owner[d] == rank;
    return n;
  };
  std::array<std::int64_t, 3> counts{owned_in(part.space->linear_block()), owned_in(part.space->quadratic_block()),
                                  owned_in(part.space->pressure_block())};
  MPI_Allreduce(MPI_IN_PLACE, counts.data(), 3, MPI_INT64_T, MPI_SUM, comm);
  v.n_linear = counts[0], v.n_quadratic = counts[1], v.n_pressure = counts[2];
  return v;
}

}  // namespace stiction::scene
