#include "mesh/local_mesh.hpp"

#include <fmt/format.h>

#include <limits>

#include "common/all_to_all.hpp"
#include "common/distributed_prefix.hpp"
#include "common/error.hpp"
#include "mesh/part_records.hpp"

namespace stiction::mesh {

namespace {

using detail::local_index;

// The local edges by low end: those of vertex v are [first[v], first[v + 1]) (local edges
// are sorted by (lo, hi)).
std::vector<int> first_edge_of_vertex(int n_vertices, const EdgeTopology& topo) {
  std::vector<int> first(n_vertices + 1, 0);
  for (const auto& e : topo.edges) ++first[e[0] + 1];
  for (int v = 0; v < n_vertices; ++v) first[v + 1] += first[v];
  return first;
}

// The whole mesh numbers its edges lexicographically by (lo, hi), so edge (a, b) is
// prefix(a) + (the rank of b among a's higher neighbours), where prefix(a) counts the edges
// whose low end is below a. A vertex of an own cell has its whole star in the part (the
// vertex layer), so the part knows all its edges; a's count is given by its owner. The
// edges whose low end is no own cell's vertex are left at -1.
GlobalEdges own_edge_ids(MPI_Comm comm, const LocalMesh& part, const EdgeTopology& topo) {
  const int nv = part.mesh.n_vertices();
  const std::vector<int> owner = vertex_owners(part), first_edge = first_edge_of_vertex(nv, topo);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<PetscInt> counted, wanted;
  std::vector<PetscScalar> counts;
  for (int v = 0; v < nv; ++v) {
    if (owner[v] < 0) continue;
    wanted.push_back(part.vertex_ids[v]);
    if (owner[v] != rank) continue;
    counted.push_back(part.vertex_ids[v]);
    counts.push_back(first_edge[v + 1] - first_edge[v]);
  }
  long long total = 0;
  const auto prefix = exclusive_prefix(comm, part.n_global_vertices, counted, counts, wanted, &total);
  if (total > std::numeric_limits<int>::max())
    throw Error(fmt::format("refinement: {} edges exceed 32-bit vertex ids", total));
  GlobalEdges ids;
  ids.n_global = static_cast<int>(total);
  ids.id.assign(topo.edges.size(), -1);
  size_t k = 0;
  for (int v = 0; v < nv; ++v) {
    if (owner[v] < 0) continue;
    const long long base = prefix[k++];
    for (int e = first_edge[v]; e < first_edge[v + 1]; ++e) ids.id[e] = static_cast<int>(base + (e - first_edge[v]));
  }
  return ids;
}

// The other edges of the ghost cells: their low end's star is not in the part, but the
// cell's owner has them numbered (an own cell's vertices have whole stars there). Each is
// asked of the owner of a ghost cell holding it, by its vertices' global ids.
void fetch_ghost_edge_ids(MPI_Comm comm, const LocalMesh& part, const EdgeTopology& topo, GlobalEdges& ids) {
  const Mesh& m = part.mesh;
  const int nve = n_simplex_edges(m.dim);
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<std::vector<int>> questions(size), asked(size);  // (lo, hi) global; local edge asked
  std::vector<char> pending(topo.edges.size(), 0);
  for (int c = part.n_own_cells; c < m.n_cells(); ++c)
    for (int k = 0; k < nve; ++k) {
      const int e = topo.cell_edges[static_cast<size_t>(c) * nve + k];
      if (ids.id[e] >= 0 || pending[e]) continue;
      pending[e] = 1;
      const int owner = part.cell_owner[c];
      questions[owner].insert(questions[owner].end(), {part.vertex_ids[topo.edges[e][0]], part.vertex_ids[topo.edges[e][1]]});
      asked[owner].push_back(e);
    }
  const auto received = all_to_all(comm, questions, MPI_INT);
  std::vector<std::vector<int>> answers(size);
  for (int from = 0; from < size; ++from)
    for (size_t q = 0; q < received[from].size(); q += 2) {
      const int e = topo.find(local_index(part.vertex_ids, received[from][q]), local_index(part.vertex_ids, received[from][q + 1]));
      if (e < 0 || ids.id[e] < 0)
        throw Error(fmt::format("local mesh: edge ({}, {}) of an own cell is not numbered", received[from][q], received[from][q + 1]),
                    ErrorKind::Internal);
      answers[from].push_back(ids.id[e]);
    }
  const auto replies = all_to_all(comm, answers, MPI_INT);
  for (int owner = 0; owner < size; ++owner)
    for (size_t i = 0; i < asked[owner].size(); ++i) ids.id[asked[owner][i]] = replies[owner][i];
}

}  // namespace

GlobalEdges global_edge_ids(MPI_Comm comm, const LocalMesh& part, const EdgeTopology& edges) {
  GlobalEdges ids = own_edge_ids(comm, part, edges);
  fetch_ghost_edge_ids(comm, part, edges, ids);
  return ids;
}

}  // namespace stiction::mesh
