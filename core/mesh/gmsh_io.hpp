#pragma once
// Gmsh as the mesh source: read .msh (version 4, ASCII or binary; physical groups become
// tags, physical names become tag names) and generate the built-in geometries through the
// Gmsh C++ API with the OpenCASCADE kernel. Higher-order input cells keep their corners.
#include <array>
#include <string>

#include "mesh/mesh.hpp"

namespace stiction::mesh {

Mesh read_msh(const std::string& path);

// Box [0,lx]x[0,ly]x[0,lz] (3D) or rectangle [0,lx]x[0,ly] (2D) meshed with target size h.
// Facet tags: xmin=1 xmax=2 ymin=3 ymax=4 zmin=5 zmax=6; cell tag 1 named "body".
Mesh generate_box(int dim, const std::array<double, 3>& lengths, double h);

// Writes the geometry above as a .msh 4.1 file (binary or ASCII), for tests and users.
void write_box_msh(int dim, const std::array<double, 3>& lengths, double h,
                   const std::string& path, bool binary);

}  // namespace stiction::mesh
