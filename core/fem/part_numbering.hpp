#pragma once
// The whole space's numbering of the unknowns of a mesh part (mesh::LocalMesh): the id that
// FieldSpace gives each of the part's nodes and pressure dofs on the whole mesh, computed
// from the part alone. Nodes are the vertices, then (P2) the edges: a vertex keeps its
// global id, an edge node is n_global_vertices + the edge's global id. Pressures are
// numbered in vertex order over the vertices of mixed bodies. With these a process holding
// only its part can address the Newton system's unknowns as a whole-mesh run does, so a
// distributed run keeps one numbering on any process count.
#include <vector>

#include <mpi.h>

#include "fem/field_space.hpp"
#include "mesh/local_mesh.hpp"

namespace stiction::fem {

struct PartNumbering {
  std::vector<int> node;      // global node of each node of the part's space
  std::vector<int> pressure;  // global pressure index (within the pressure block) of each part vertex, -1 without
  int n_global_nodes = 0, n_global_pressures = 0;
};

// space: the FieldSpace of part.mesh (its vertex_has_pressure true at the part's vertices
// of mixed cells). Collective.
PartNumbering number_part_space(MPI_Comm comm, const mesh::LocalMesh& part, const FieldSpace& space);

}  // namespace stiction::fem
