#pragma once
// Internal to core/mesh: the Gmsh session the mesh sources share (gmsh_io.cpp,
// grooved_block.cpp). Gmsh keeps one global model and global options; these helpers start
// each use from a known state, turn Gmsh's failures into stiction::Error and read the
// current model back as a Mesh. Not part of the public mesh API.
#include <fmt/format.h>

#include <exception>
#include <string>

#include "common/error.hpp"
#include "mesh/mesh.hpp"

namespace stiction::mesh::detail {

// Initialises Gmsh once per process, resets the options generators change to Gmsh's
// defaults (one thread: deterministic meshes) and clears the model.
void gmsh_begin();

// Gmsh's last logged error, or "" (never throws).
std::string gmsh_last_error();

// Runs a Gmsh call sequence and turns whatever Gmsh throws into a stiction::Error.
template <class F>
auto with_gmsh(const std::string& context, F&& f) {
  try {
    return f();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(fmt::format("{}: {}", context, e.what()));
  } catch (...) {
    const std::string last = gmsh_last_error();
    throw Error(fmt::format("{}: {}", context, last.empty() ? "Gmsh failed" : last));
  }
}

// Builds a Mesh from Gmsh's current model. Cells are the elements of top dimension in
// physical groups (all of them when there is none); facets those of dimension - 1 in
// physical groups. Only vertices used by cells are kept; the edge nodes of second-order
// cells that lie off their chords become Mesh::edge_midpoints.
Mesh extract_current_model(const std::string& what);

// Where the current model has curved curves or surfaces, makes its mesh second order with
// the edge nodes on the CAD entities, so extract_current_model records the curved edges'
// midpoints (Mesh::edge_midpoints). Flat models stay first order.
void place_edge_midpoints_on_geometry();

// Meshes the current model in `dim` with sizes clamped to [h_min, h] (h_min <= 0: h),
// 3D Delaunay, then place_edge_midpoints_on_geometry.
void set_size_and_generate(int dim, double h, double h_min = 0);

}  // namespace stiction::mesh::detail
