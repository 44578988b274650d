#pragma once
// Gmsh as the mesh source: read .msh (version 4, ASCII or binary; physical groups become
// tags, physical names become tag names) and generate the built-in geometries through the
// Gmsh C++ API with the OpenCASCADE kernel. Higher-order input cells keep their corners.
#include <array>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace stiction::mesh {

Mesh read_msh(const std::string& path);

// Box [0,lx]x[0,ly]x[0,lz] (3D) or rectangle [0,lx]x[0,ly] (2D) meshed with target size h.
// Facet tags: xmin=1 xmax=2 ymin=3 ymax=4 zmin=5 zmax=6; cell tag 1 named "body".
Mesh generate_box(int dim, const std::array<double, 3>& lengths, double h);

// Plane polygon (points x0 y0 x1 y1 ..., counter-clockwise) with side i (point i to i+1)
// named side_names[i]; meshed in 2D, or extruded along z by `thickness` > 0 and meshed in
// 3D, with the extra faces named "front" (z = 0) and "back" (z = thickness). Cell tag 1 "body".
Mesh generate_polygon(const std::vector<double>& points, const std::vector<std::string>& side_names, double h,
                      double thickness = 0);

// Writes the geometry above as a .msh 4.1 file (binary or ASCII), for tests and users.
void write_box_msh(int dim, const std::array<double, 3>& lengths, double h,
                   const std::string& path, bool binary);

}  // namespace stiction::mesh
