#include "mesh/local_mesh.hpp"

#include <algorithm>
#include <numeric>
#include <set>

#include "common/all_to_all.hpp"
#include "mesh/part_records.hpp"

namespace stiction::mesh {

namespace {

using namespace detail;

// Records as MPI sends them: a header of four counts, then per record its ints and doubles
// (coordinates as three doubles whatever the dimension).
void pack(const PartRecords& r, std::vector<int>& ints, std::vector<double>& reals) {
  ints.insert(ints.end(), {static_cast<int>(r.cells.size()), static_cast<int>(r.vertices.size()),
                           static_cast<int>(r.facets.size()), static_cast<int>(r.midpoints.size())});
  for (const CellRecord& c : r.cells) ints.insert(ints.end(), {c.id, c.owner, c.tag, c.v[0], c.v[1], c.v[2], c.v[3]});
  for (const VertexRecord& v : r.vertices) ints.push_back(v.id), reals.insert(reals.end(), v.x.begin(), v.x.end());
  for (const FacetRecord& f : r.facets) ints.insert(ints.end(), {f.id, f.tag, f.v[0], f.v[1], f.v[2]});
  for (const MidpointRecord& p : r.midpoints)
    ints.insert(ints.end(), p.edge.begin(), p.edge.end()), reals.insert(reals.end(), p.x.begin(), p.x.end());
}

// Appends every packed part in (ints, reals) to r.
void unpack(const std::vector<int>& ints, const std::vector<double>& reals, PartRecords& r) {
  size_t i = 0, x = 0;
  auto point = [&] {
    std::array<double, 3> p{reals[x], reals[x + 1], reals[x + 2]};
    x += 3;
    return p;
  };
  while (i < ints.size()) {
    const int nc = ints[i], nv = ints[i + 1], nf = ints[i + 2], np = ints[i + 3];
    i += 4;
    for (int k = 0; k < nc; ++k, i += 7) r.cells.push_back({ints[i], ints[i + 1], ints[i + 2], {ints[i + 3], ints[i + 4], ints[i + 5], ints[i + 6]}});
    for (int k = 0; k < nv; ++k) r.vertices.push_back({ints[i++], point()});
    for (int k = 0; k < nf; ++k, i += 5) r.facets.push_back({ints[i], ints[i + 1], {ints[i + 2], ints[i + 3], ints[i + 4]}});
    for (int k = 0; k < np; ++k, i += 2) r.midpoints.push_back({{ints[i], ints[i + 1]}, point()});
  }
}


// The processes other than the owner whose parts hold own cell c as a ghost: the owners of
// the cells that share a vertex with c (all in the part, since c's vertices have whole stars).
std::vector<std::set<int>> ghost_holders(const LocalMesh& part) {
  const Mesh& m = part.mesh;
  const int nvc = m.vertices_per_cell();
  std::vector<std::vector<int>> owners_at(m.n_vertices());
  for (int c = 0; c < m.n_cells(); ++c)
    for (int k = 0; k < nvc; ++k) owners_at[m.cell(c)[k]].push_back(part.cell_owner[c]);
  std::vector<std::set<int>> holders(part.n_own_cells);
  for (int c = 0; c < part.n_own_cells; ++c) {
    for (int k = 0; k < nvc; ++k) holders[c].insert(owners_at[m.cell(c)[k]].begin(), owners_at[m.cell(c)[k]].end());
    holders[c].erase(part.cell_owner[c]);
  }
  return holders;
}

// From the refined part's local numbers to global ids.
struct Renumbering {
  std::vector<int> fine_vertex_ids;  // global id of each fine local vertex
  std::vector<int> position;         // of each local cell among the refined cells' parents
  int children = 0, facet_children = 0;
};

// Records bound for one process (or kept), each fine vertex once.
struct Sink {
  PartRecords records;
  std::vector<char> has_vertex;  // per fine local vertex
};

// Appends own cell c's children in `fine` (mesh::refine of the part) by global ids to the
// sink, with their vertices, the children of the tagged facets on c and the curved edges of
// the children.
void add_children(const LocalMesh& part, const Mesh& fine, const Renumbering& g, int c,
                  const std::vector<std::vector<int>>& facets_of_cell, Sink& sink) {
  const int d = fine.dim, nvc = d + 1;
  PartRecords& r = sink.records;
  if (sink.has_vertex.empty()) sink.has_vertex.assign(static_cast<size_t>(fine.n_vertices()), 0);
  for (int j = 0; j < g.children; ++j) {
    const int child = g.position[c] * g.children + j;
    CellRecord rec{part.cell_ids[c] * g.children + j, part.cell_owner[c], fine.cell_tags[child], {-1, -1, -1, -1}};
    for (int k = 0; k < nvc; ++k) {
      const int v = fine.cell(child)[k];
      rec.v[k] = g.fine_vertex_ids[v];
      if (sink.has_vertex[v]) continue;
      sink.has_vertex[v] = 1;
      VertexRecord vr{rec.v[k], {0, 0, 0}};
      std::copy(fine.vertex(v), fine.vertex(v) + d, vr.x.begin());
      r.vertices.push_back(vr);
    }
    r.cells.push_back(rec);
    for (int e = 0; e < n_simplex_edges(d); ++e) {
      const auto [a, b] = simplex_edge(d, e);
      const int va = fine.cell(child)[a], vb = fine.cell(child)[b];
      const auto it = fine.edge_midpoints.find({std::min(va, vb), std::max(va, vb)});
      if (it == fine.edge_midpoints.end()) continue;
      r.midpoints.push_back({{std::min(rec.v[a], rec.v[b]), std::max(rec.v[a], rec.v[b])}, it->second});
    }
  }
  for (int f : facets_of_cell[c])
    for (int j = 0; j < g.facet_children; ++j) {
      const int ff = f * g.facet_children + j;
      FacetRecord rec{part.facet_ids[f] * g.facet_children + j, fine.facet_tags[ff], {-1, -1, -1}};
      for (int k = 0; k < d; ++k) rec.v[k] = g.fine_vertex_ids[fine.facet(ff)[k]];
      r.facets.push_back(rec);
    }
}

// The part's mesh with its cells in ascending global id (position[c]: local cell c's place).
// mesh::refine sets a child edge that several parents' children share (on a parent's face or
// edge) from each curved parent in turn, so the highest-id parent's value stays; refined in
// global order, the part gives its own cells' children the same values, since every parent
// around their edges is in the part (it shares their vertices).
Mesh in_global_order(const LocalMesh& part, std::vector<int>& position) {
  const Mesh& m = part.mesh;
  const int nc = m.n_cells(), nvc = m.vertices_per_cell();
  std::vector<int> order(nc);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return part.cell_ids[a] < part.cell_ids[b]; });
  Mesh sorted = m;
  position.assign(nc, -1);
  for (int k = 0; k < nc; ++k) {
    position[order[k]] = k;
    std::copy(m.cell(order[k]), m.cell(order[k]) + nvc, sorted.cells.begin() + static_cast<size_t>(k) * nvc);
    sorted.cell_tags[k] = m.cell_tags[order[k]];
  }
  return sorted;
}

// The tagged facets lying on each own cell of the part.
std::vector<std::vector<int>> facets_of_own_cells(const LocalMesh& part) {
  const Mesh& m = part.mesh;
  std::vector<std::pair<std::array<int, 3>, int>> by_key;
  for (int f = 0; f < m.n_facets(); ++f) by_key.push_back({facet_key(m.facet(f), m.dim), f});
  std::sort(by_key.begin(), by_key.end());
  std::vector<std::vector<int>> of_cell(part.n_own_cells);
  for (int c = 0; c < part.n_own_cells; ++c)
    for (const auto& key : cell_facet_keys(m.cell(c), m.dim)) {
      auto it = std::lower_bound(by_key.begin(), by_key.end(), std::make_pair(key, -1));
      for (; it != by_key.end() && it->first == key; ++it) of_cell[c].push_back(it->second);
    }
  return of_cell;
}

// Whether each own cell has a facet on one of the surfaces the part holds whole: every
// process holds such a cell's children on those surfaces, so its owner sends them to all.
std::vector<char> own_cells_on_surfaces(const LocalMesh& part, const std::vector<std::vector<int>>& facets_of_cell) {
  std::vector<char> on(static_cast<size_t>(part.n_own_cells), 0);
  const auto& tags = part.surface_tags;
  for (int c = 0; c < part.n_own_cells; ++c)
    for (int f : facets_of_cell[c])
      if (std::find(tags.begin(), tags.end(), part.mesh.facet_tags[f]) != tags.end()) on[c] = 1;
  return on;
}

}  // namespace

LocalMesh refine_parts(MPI_Comm comm, const LocalMesh& part) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const Mesh& coarse = part.mesh;
  const int d = coarse.dim;
  // Refining the whole part numbers its children and new vertices locally and computes
  // their coordinates and curved edges as mesh::refine does on the whole mesh; the own
  // cells' children then take their global ids, and the ghosts' children are dropped: their
  // owners send them. That holds for the cells on the surfaces held whole too: away from the
  // own cells a part lacks some parents around their edges, which the curved-edge values of
  // their children depend on, while their owner has them all.
  Renumbering g;
  const Mesh fine = refine(in_global_order(part, g.position));
  const GlobalEdges edges = global_edge_ids(comm, part, build_edges(coarse));
  g.children = d == 2 ? 4 : 8;
  g.facet_children = d == 2 ? 2 : 4;
  g.fine_vertex_ids = part.vertex_ids;
  for (int id : edges.id) g.fine_vertex_ids.push_back(part.n_global_vertices + id);

  const auto holders = ghost_holders(part);
  const auto facets_of_cell = facets_of_own_cells(part);
  const auto on_surfaces = own_cells_on_surfaces(part, facets_of_cell);
  Sink mine;
  std::vector<Sink> outgoing(size);
  for (int c = 0; c < part.n_own_cells; ++c) {
    std::set<int> destinations = holders[c];
    if (on_surfaces[c])
      for (int p = 0; p < size; ++p)
        if (p != rank) destinations.insert(p);
    for (int dest : destinations) add_children(part, fine, g, c, facets_of_cell, outgoing[dest]);
    add_children(part, fine, g, c, facets_of_cell, mine);
  }
  std::vector<std::vector<int>> out_ints(size);
  std::vector<std::vector<double>> out_reals(size);
  for (int dest = 0; dest < size; ++dest)
    if (dest != rank) pack(outgoing[dest].records, out_ints[dest], out_reals[dest]);
  unpack(concatenated(all_to_all(comm, out_ints, MPI_INT)), concatenated(all_to_all(comm, out_reals, MPI_DOUBLE)), mine.records);

  LocalMesh finer = number_part(mine.records, coarse, rank, part.surface_tags);
  finer.n_global_vertices = part.n_global_vertices + edges.n_global;
  finer.n_global_cells = part.n_global_cells * g.children;
  finer.n_global_facets = part.n_global_facets * g.facet_children;
  return finer;
}

}  // namespace stiction::mesh
