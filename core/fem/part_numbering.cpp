#include "fem/part_numbering.hpp"

#include "common/distributed_prefix.hpp"

namespace stiction::fem {

namespace {

// Pressure dofs are numbered in global vertex order: each is counted once, by its vertex's
// owner (whose part holds every cell around the vertex, so it knows whether a mixed body
// reaches it), and numbered by the exclusive prefix of those counts.
void number_pressures(MPI_Comm comm, const mesh::LocalMesh& part, const FieldSpace& space, PartNumbering& n) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::vector<int> owner = mesh::vertex_owners(part);
  std::vector<PetscInt> counted, wanted;
  std::vector<PetscScalar> ones;
  for (int v = 0; v < space.n_vertices(); ++v) {
    if (space.pressure_dof(v) < 0) continue;
    wanted.push_back(part.vertex_ids[v]);
    if (owner[v] == rank) counted.push_back(part.vertex_ids[v]), ones.push_back(1.0);
  }
  long long total = 0;
  const auto prefix = exclusive_prefix(comm, part.n_global_vertices, counted, ones, wanted, &total);
  n.n_global_pressures = static_cast<int>(total);
  n.pressure.assign(space.n_vertices(), -1);
  size_t k = 0;
  for (int v = 0; v < space.n_vertices(); ++v)
    if (space.pressure_dof(v) >= 0) n.pressure[v] = static_cast<int>(prefix[k++]);
}

}  // namespace

PartNumbering number_part_space(MPI_Comm comm, const mesh::LocalMesh& part, const FieldSpace& space) {
  PartNumbering n;
  n.node = part.vertex_ids;
  n.n_global_nodes = part.n_global_vertices;
  if (is_quadratic(space.kind())) {
    const mesh::GlobalEdges edges = mesh::global_edge_ids(comm, part, space.edges());
    for (int id : edges.id) n.node.push_back(part.n_global_vertices + id);
    n.n_global_nodes += edges.n_global;
  }
  // Every process takes part in the scan, with a pressure field or not.
  int any_pressure = space.has_pressure(), some_process = 0;
  MPI_Allreduce(&any_pressure, &some_process, 1, MPI_INT, MPI_MAX, comm);
  if (some_process) number_pressures(comm, part, space, n);
  else n.pressure.assign(space.n_vertices(), -1);
  return n;
}

}  // namespace stiction::fem
