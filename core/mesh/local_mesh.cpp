#include "mesh/local_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/error.hpp"
#include "mesh/part_records.hpp"

namespace stiction::mesh {

namespace detail {

namespace {

// v sorted by key without repeats. The (key, position) pairs are sorted rather than the
// records, which are several times larger (a part refined to level 2 sorts millions).
template <class T, class Key>
void sort_unique(std::vector<T>& v, Key key) {
  using K = decltype(key(v.front()));
  std::vector<std::pair<K, size_t>> order;
  order.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i) order.push_back({key(v[i]), i});
  std::sort(order.begin(), order.end());
  std::vector<T> unique;
  for (size_t i = 0; i < order.size(); ++i)
    if (i == 0 || order[i].first != order[i - 1].first) unique.push_back(v[order[i].second]);
  v.swap(unique);
}

bool contains(const std::vector<int>& sorted, int x) { return std::binary_search(sorted.begin(), sorted.end(), x); }

// The own cells (owner == rank), then the ghosts: those that share a vertex with them and
// those with a face among surface_keys (sorted facet keys), each group in ascending id
// (records sorted by id, without repeats).
std::vector<const CellRecord*> own_cells_and_layer(const std::vector<CellRecord>& cells, int rank, int nvc,
                                                   const std::vector<std::array<int, 3>>& surface_keys) {
  const auto on_surface = [&](const CellRecord& c) {
    if (surface_keys.empty()) return false;
    for (const auto& key : cell_facet_keys(c.v.data(), nvc - 1))
      if (std::binary_search(surface_keys.begin(), surface_keys.end(), key)) return true;
    return false;
  };
  std::vector<int> own_vertices;
  for (const CellRecord& c : cells)
    if (c.owner == rank) own_vertices.insert(own_vertices.end(), c.v.begin(), c.v.begin() + nvc);
  std::sort(own_vertices.begin(), own_vertices.end());
  own_vertices.erase(std::unique(own_vertices.begin(), own_vertices.end()), own_vertices.end());
  std::vector<const CellRecord*> kept;
  for (const CellRecord& c : cells)
    if (c.owner == rank) kept.push_back(&c);
  for (const CellRecord& c : cells)
    if (c.owner != rank &&
        (std::any_of(c.v.begin(), c.v.begin() + nvc, [&](int v) { return contains(own_vertices, v); }) || on_surface(c)))
      kept.push_back(&c);
  return kept;
}

// The part's vertices (those of its cells, ascending) with their coordinates.
void add_vertices(LocalMesh& part, const std::vector<const CellRecord*>& cells, std::vector<VertexRecord>& vertices) {
  const int d = part.mesh.dim;
  for (const CellRecord* c : cells) part.vertex_ids.insert(part.vertex_ids.end(), c->v.begin(), c->v.begin() + d + 1);
  std::sort(part.vertex_ids.begin(), part.vertex_ids.end());
  part.vertex_ids.erase(std::unique(part.vertex_ids.begin(), part.vertex_ids.end()), part.vertex_ids.end());
  sort_unique(vertices, [](const VertexRecord& v) { return v.id; });
  std::vector<int> record_ids;
  for (const VertexRecord& v : vertices) record_ids.push_back(v.id);
  for (int id : part.vertex_ids) {
    const VertexRecord& v = vertices[local_index(record_ids, id)];
    part.mesh.coords.insert(part.mesh.coords.end(), v.x.begin(), v.x.begin() + d);
  }
}

void add_cells(LocalMesh& part, const std::vector<const CellRecord*>& cells) {
  for (const CellRecord* c : cells) {
    part.cell_ids.push_back(c->id);
    part.cell_owner.push_back(c->owner);
    part.mesh.cell_tags.push_back(c->tag);
    for (int k = 0; k <= part.mesh.dim; ++k) part.mesh.cells.push_back(local_index(part.vertex_ids, c->v[k]));
  }
}

// The tagged facets that are faces of the part's cells.
void add_facets(LocalMesh& part, const std::vector<const CellRecord*>& cells, std::vector<FacetRecord>& facets) {
  const int d = part.mesh.dim;
  std::vector<std::array<int, 3>> faces;
  for (const CellRecord* c : cells)
    for (const auto& key : cell_facet_keys(c->v.data(), d)) faces.push_back(key);
  std::sort(faces.begin(), faces.end());
  sort_unique(facets, [](const FacetRecord& f) { return f.id; });
  for (const FacetRecord& f : facets) {
    if (!std::binary_search(faces.begin(), faces.end(), facet_key(f.v.data(), d))) continue;
    part.facet_ids.push_back(f.id);
    part.mesh.facet_tags.push_back(f.tag);
    for (int k = 0; k < d; ++k) part.mesh.facets.push_back(local_index(part.vertex_ids, f.v[k]));
  }
}

// The curved edges among the part's cells' edges.
void add_curved_edges(LocalMesh& part, const std::vector<const CellRecord*>& cells, std::vector<MidpointRecord>& midpoints) {
  const int d = part.mesh.dim;
  sort_unique(midpoints, [](const MidpointRecord& p) { return p.edge; });
  for (const CellRecord* c : cells)
    for (int e = 0; e < n_simplex_edges(d); ++e) {
      const auto [i, j] = simplex_edge(d, e);
      const std::array<int, 2> edge{std::min(c->v[i], c->v[j]), std::max(c->v[i], c->v[j])};
      const auto it = std::lower_bound(midpoints.begin(), midpoints.end(), edge,
                                       [](const MidpointRecord& p, const std::array<int, 2>& e) { return p.edge < e; });
      if (it != midpoints.end() && it->edge == edge)
        part.mesh.edge_midpoints[{local_index(part.vertex_ids, edge[0]), local_index(part.vertex_ids, edge[1])}] = it->x;
    }
}

}  // namespace

int local_index(const std::vector<int>& sorted_ids, int id) {
  const auto it = std::lower_bound(sorted_ids.begin(), sorted_ids.end(), id);
  if (it == sorted_ids.end() || *it != id)
    throw Error(fmt::format("local mesh: global vertex {} is not held by this process", id), ErrorKind::Internal);
  return static_cast<int>(it - sorted_ids.begin());
}

LocalMesh number_part(PartRecords& r, const Mesh& names, int rank, const std::vector<int>& surface_tags) {
  LocalMesh part;
  part.surface_tags = surface_tags;
  std::vector<std::array<int, 3>> surface_keys;
  for (const FacetRecord& f : r.facets)
    if (std::find(surface_tags.begin(), surface_tags.end(), f.tag) != surface_tags.end())
      surface_keys.push_back(facet_key(f.v.data(), names.dim));
  std::sort(surface_keys.begin(), surface_keys.end());
  part.mesh.dim = names.dim;
  part.mesh.cell_tag_names = names.cell_tag_names;
  part.mesh.facet_tag_names = names.facet_tag_names;
  sort_unique(r.cells, [](const CellRecord& c) { return c.id; });
  const auto cells = own_cells_and_layer(r.cells, rank, names.dim + 1, surface_keys);
  part.n_own_cells = static_cast<int>(std::count_if(cells.begin(), cells.end(), [&](const CellRecord* c) { return c->owner == rank; }));
  add_vertices(part, cells, r.vertices);
  add_cells(part, cells);
  add_facets(part, cells, r.facets);
  add_curved_edges(part, cells, r.midpoints);
  return part;
}

}  // namespace detail

std::vector<int> vertex_owners(const LocalMesh& part) {
  const Mesh& m = part.mesh;
  const int nv = m.n_vertices();
  std::vector<int> owner(nv, -1), lowest_cell(nv, -1);
  for (int c = 0; c < m.n_cells(); ++c)
    for (int k = 0; k < m.vertices_per_cell(); ++k) {
      const int v = m.cell(c)[k];
      if (lowest_cell[v] < 0 || part.cell_ids[c] < lowest_cell[v]) lowest_cell[v] = part.cell_ids[c], owner[v] = part.cell_owner[c];
    }
  std::vector<char> star_held(nv, 0);
  for (int c = 0; c < part.n_own_cells; ++c)
    for (int k = 0; k < m.vertices_per_cell(); ++k) star_held[m.cell(c)[k]] = 1;
  for (int v = 0; v < nv; ++v)
    if (!star_held[v]) owner[v] = -1;
  return owner;
}

LocalMesh local_part(const Mesh& whole, const std::vector<int>& cell_owner, int rank,
                     const std::vector<int>& surface_tags) {
  const int d = whole.dim, nvc = d + 1;
  if (static_cast<int>(cell_owner.size()) != whole.n_cells())
    throw Error(fmt::format("local_part: {} cell owners for {} cells", cell_owner.size(), whole.n_cells()), ErrorKind::Internal);
  detail::PartRecords r;
  for (int c = 0; c < whole.n_cells(); ++c) {
    detail::CellRecord rec{c, cell_owner[c], whole.cell_tags[c], {-1, -1, -1, -1}};
    std::copy(whole.cell(c), whole.cell(c) + nvc, rec.v.begin());
    r.cells.push_back(rec);
  }
  for (int v = 0; v < whole.n_vertices(); ++v) {
    detail::VertexRecord rec{v, {0, 0, 0}};
    std::copy(whole.vertex(v), whole.vertex(v) + d, rec.x.begin());
    r.vertices.push_back(rec);
  }
  for (int f = 0; f < whole.n_facets(); ++f) {
    detail::FacetRecord rec{f, whole.facet_tags[f], {-1, -1, -1}};
    std::copy(whole.facet(f), whole.facet(f) + d, rec.v.begin());
    r.facets.push_back(rec);
  }
  for (const auto& [edge, x] : whole.edge_midpoints) r.midpoints.push_back({edge, x});
  LocalMesh part = detail::number_part(r, whole, rank, surface_tags);
  part.n_global_vertices = whole.n_vertices();
  part.n_global_cells = whole.n_cells();
  part.n_global_facets = whole.n_facets();
  return part;
}

}  // namespace stiction::mesh
