#pragma once
// One process's part of a mesh divided among MPI processes: the cells it owns and the layer
// of cells that share a vertex with them (its ghosts), numbered locally, with the id every
// vertex, cell and facet has in the whole mesh. The layer gives every vertex of an own cell
// its whole star, which is what a process needs to number its own cells' edges and to
// assemble the rows of their nodes.
//
// refine_parts() refines the parts where they are, each process its own cells: children,
// facets and new vertices get the ids mesh::refine() gives them on the whole mesh, so a mesh
// refined in parts is the refined whole mesh divided (bit for bit, coordinates and curved
// edges included). A level's numbering thus does not depend on the process count, and a mesh
// need only be whole at the coarse level that is partitioned. (Scenes are solved on parts:
// scene::divide_scene, which `stiction solve` uses on several processes; with contact a
// part also holds the contact surfaces whole, at every level.)
#include <vector>

#include <mpi.h>

#include "mesh/mesh.hpp"

namespace stiction::mesh {

struct LocalMesh {
  // Local numbering. Cells: the own ones first, then the ghosts, each in ascending global
  // id; vertices and facets in ascending global id (so a local edge (lo, hi) is the global
  // edge in the same order). Facets: the tagged facets of the local cells.
  Mesh mesh;
  std::vector<int> vertex_ids, cell_ids, facet_ids;  // global id of each local entity
  std::vector<int> cell_owner;                       // owning process of each local cell
  int n_own_cells = 0;
  // Facet tags whose facets the part holds whole, with the cells on them as ghosts (the
  // contact surfaces, which every process evaluates whole).
  std::vector<int> surface_tags;
  int n_global_vertices = 0, n_global_cells = 0, n_global_facets = 0;
};

// The owner of each vertex of the part: the owner of the lowest-id cell around it (the rule
// fem::DofLayout gives nodes), or -1 where the part does not hold the vertex's whole star
// (a vertex of ghost cells only), which is where it could not tell.
std::vector<int> vertex_owners(const LocalMesh& part);

// The global id of every edge of the part (edges.edges[e] has id[e]): the whole mesh's
// edge numbering (mesh::build_edges, lexicographic by global vertex ids), which also numbers
// the P2 nodes (n_global_vertices + id) and the next level's new vertices. Collective.
struct GlobalEdges {
  std::vector<int> id;
  int n_global = 0;  // edges of the whole mesh
};
GlobalEdges global_edge_ids(MPI_Comm comm, const LocalMesh& part, const EdgeTopology& edges);

// Process `rank`'s part of `whole`, whose cell c belongs to process cell_owner[c]; with
// surface_tags, also every cell with a facet of those tags, so that the part holds those
// surfaces whole (their vertices away from the own cells have no star in the part: their
// owner is -1 in vertex_owners).
LocalMesh local_part(const Mesh& whole, const std::vector<int>& cell_owner, int rank,
                     const std::vector<int>& surface_tags = {});

// One uniform refinement of every process's part (collective over comm): the children of a
// cell stay with its owner. A part that holds surfaces whole (surface_tags) holds them whole
// refined: the owner of a cell on them sends its children to every process.
LocalMesh refine_parts(MPI_Comm comm, const LocalMesh& part);

}  // namespace stiction::mesh
