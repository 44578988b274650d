#include "fem/part_ownership.hpp"

#include <algorithm>

#include "common/petsc.hpp"

namespace stiction::fem {

namespace {

using PetscAO = PetscOwner<AO, AODestroy>;

// The owner of each node of the part's space whose cells around it are all in the part (the
// nodes of own cells); -1 for the others, which this process cannot own.
std::vector<int> node_owners(const mesh::LocalMesh& part, const FieldSpace& space) {
  std::vector<int> owner = mesh::vertex_owners(part);
  if (!is_quadratic(space.kind())) return owner;
  const mesh::Mesh& m = part.mesh;
  const mesh::EdgeTopology& topo = space.edges();
  const int nve = mesh::n_simplex_edges(m.dim);
  std::vector<int> lowest_cell(topo.edges.size(), -1), edge_owner(topo.edges.size(), -1);
  std::vector<char> of_own_cell(topo.edges.size(), 0);
  for (int c = 0; c < m.n_cells(); ++c)
    for (int k = 0; k < nve; ++k) {
      const int e = topo.cell_edges[static_cast<size_t>(c) * nve + k];
      if (c < part.n_own_cells) of_own_cell[e] = 1;
      if (lowest_cell[e] < 0 || part.cell_ids[c] < lowest_cell[e]) lowest_cell[e] = part.cell_ids[c], edge_owner[e] = part.cell_owner[c];
    }
  for (size_t e = 0; e < topo.edges.size(); ++e) owner.push_back(of_own_cell[e] ? edge_owner[e] : -1);
  return owner;
}

}  // namespace

PartOwnership own_part_unknowns(MPI_Comm comm, const mesh::LocalMesh& part, const FieldSpace& space,
                                const PartNumbering& numbering, const std::vector<int>& extra_vertices) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const int d = space.dim();
  const std::vector<int> owner = node_owners(part, space);
  PartOwnership o;
  const size_t n_held = static_cast<size_t>(space.n_dofs()) + extra_vertices.size();
  o.app.resize(n_held);
  o.owner.assign(n_held, -1);
  for (int node = 0; node < space.n_nodes(); ++node)
    for (int k = 0; k < d; ++k) {
      o.app[static_cast<size_t>(node) * d + k] = static_cast<PetscInt>(numbering.node[node]) * d + k;
      o.owner[static_cast<size_t>(node) * d + k] = owner[node];
    }
  const PetscInt pressure_block = static_cast<PetscInt>(numbering.n_global_nodes) * d;
  for (int v = 0; v < space.n_vertices(); ++v)
    if (space.pressure_dof(v) >= 0) {
      o.app[space.pressure_dof(v)] = pressure_block + numbering.pressure[v];
      o.owner[space.pressure_dof(v)] = owner[v];
    }

  // The extra unknowns follow the whole space's in app order, each owned by its vertex's
  // owner, as fem::DofLayout orders them over the whole mesh.
  const PetscInt extra_block = pressure_block + numbering.n_global_pressures;
  for (size_t k = 0; k < extra_vertices.size(); ++k) {
    o.app[static_cast<size_t>(space.n_dofs()) + k] = extra_block + static_cast<PetscInt>(k);
    o.owner[static_cast<size_t>(space.n_dofs()) + k] = owner[extra_vertices[k]];
  }
  // The owned unknowns in app order take this process's range of PETSc indices.
  std::vector<PetscInt> owned_app;
  for (size_t i = 0; i < o.app.size(); ++i)
    if (o.owner[i] == rank) owned_app.push_back(o.app[i]);
  std::sort(owned_app.begin(), owned_app.end());
  o.n_owned = static_cast<PetscInt>(owned_app.size());
  MPI_Exscan(&o.n_owned, &o.first_owned, 1, MPIU_INT, MPI_SUM, comm);
  if (rank == 0) o.first_owned = 0;  // MPI_Exscan leaves rank 0's result undefined
  std::vector<PetscInt> owned_petsc(owned_app.size());
  for (size_t j = 0; j < owned_petsc.size(); ++j) owned_petsc[j] = o.first_owned + static_cast<PetscInt>(j);

  PetscAO ao;
  STICTION_PETSC(AOCreateMemoryScalable(comm, o.n_owned, owned_app.data(), owned_petsc.data(), ao.out()));
  o.petsc = o.app;
  STICTION_PETSC(AOApplicationToPetsc(ao, static_cast<PetscInt>(o.petsc.size()), o.petsc.data()));
  return o;
}

}  // namespace stiction::fem
