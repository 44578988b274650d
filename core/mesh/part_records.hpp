#pragma once
// What the mesh parts are built from (mesh/local_mesh.cpp) and exchanged as (refinement in
// parts, mesh/refine_parts.cpp): cells, vertices, facets and curved edges by global ids.
#include <array>
#include <vector>

#include "mesh/local_mesh.hpp"

namespace stiction::mesh::detail {

// A part described by global ids, in any order and with repeats, before it is numbered
// locally: what a process knows of its own cells and receives of its neighbours'.
struct CellRecord {
  int id, owner, tag;
  std::array<int, 4> v;  // global vertex ids (dim + 1 used)
};
struct FacetRecord {
  int id, tag;
  std::array<int, 3> v;  // global vertex ids (dim used), in the facet's order
};
struct VertexRecord {
  int id;
  std::array<double, 3> x;
};
struct MidpointRecord {
  std::array<int, 2> edge;  // global (lo, hi)
  std::array<double, 3> x;
};
struct PartRecords {
  std::vector<CellRecord> cells;
  std::vector<VertexRecord> vertices;
  std::vector<FacetRecord> facets;
  std::vector<MidpointRecord> midpoints;
};

// Process `rank`'s part out of records that hold at least its own cells, their vertex layer,
// the cells on the facets tagged surface_tags and everything on those cells: the records of
// other cells are dropped. Tag names and the dimension come from `names`; the global counts
// are left to the caller.
LocalMesh number_part(PartRecords& r, const Mesh& names, int rank, const std::vector<int>& surface_tags = {});

// The position of a global id in the part's ascending ids (an internal error if absent).
int local_index(const std::vector<int>& sorted_ids, int id);

}  // namespace stiction::mesh::detail
