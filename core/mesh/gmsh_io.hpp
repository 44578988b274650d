#pragma once
// Gmsh as the mesh source: read .msh (version 4, ASCII or binary; physical groups become
// tags, physical names become tag names) and generate the built-in geometries through the
// Gmsh C++ API with the OpenCASCADE kernel. Higher-order input cells keep their corners.
#include <array>
#include <map>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace stiction::mesh {

Mesh read_msh(const std::string& path);

// Meshes a Gmsh .geo script (built-in or OpenCASCADE kernel, its own physical groups and
// size fields) through the Gmsh library, in the script's top dimension, with every element
// size multiplied by size_factor: a finer level is a new mesh of the same geometry, so
// vertices on curved boundaries stay on them.
Mesh mesh_geo(const std::string& path, double size_factor);

// Element size `size` on the named boundary, growing linearly to the generator's h at
// `distance` from it (Gmsh Distance and Threshold fields, the background size).
struct BoundarySizeField {
  std::string boundary;
  double size = 0;
  double distance = 0;
};

// Box [0,lx]x[0,ly]x[0,lz] (3D) or rectangle [0,lx]x[0,ly] (2D) meshed with target size h.
// Facet tags: xmin=1 xmax=2 ymin=3 ymax=4 zmin=5 zmax=6; cell tag 1 named "body".
Mesh generate_box(int dim, const std::array<double, 3>& lengths, double h);

// A plane polygon (points counter-clockwise), side i (point i to i+1) named names[i]; a
// side with an arc centre is the circular arc from point i to i+1 about it (both points
// must be equidistant from it). Meshed in 2D, or extruded along z by `thickness` > 0 and
// meshed in 3D, with the extra faces named "front" (z = 0) and "back" (z = thickness).
// point_sizes (one per point, each <= h; empty: uniform h) grade the mesh towards points,
// size_fields towards named sides (the smallest size wins where they overlap); `scale`
// multiplies every size (a finer mesh of the same, exactly curved, geometry).
// Cell tag 1 "body".
struct PolygonSpec {
  std::vector<double> xy;
  std::vector<std::string> names;
  double h = 0;
  double thickness = 0;
  std::vector<double> point_sizes;
  std::map<int, std::array<double, 2>> arc_centers;  // side -> centre
  std::vector<BoundarySizeField> size_fields;         // sizes scale with `scale` too
  double scale = 1;
};
Mesh generate_polygon(const PolygonSpec& spec);

// One eighth of a ball of radius R centred at (0, R, 0): x >= 0, z >= 0, y <= R, so its
// lowest point (the pole) is the origin. Faces "surface" (spherical), "top" (y = R),
// "symmetry-x" (x = 0), "symmetry-z" (z = 0); cell tag 1 "body". Element size
// contact_size within contact_zone of the pole, growing to h at 0.6 R; `scale`
// multiplies every size (a finer mesh of the same, exactly spherical, geometry).
struct SphereOctantSpec {
  double radius = 1;
  double h = 0;
  double contact_size = 0;
  double contact_zone = 0;
  double scale = 1;
  // The ball lies above its pole (centre (0, R, 0), flat face "top" at y = R) or, with
  // below, under it (centre (0, -R, 0), flat face "base" at y = -R).
  bool below = false;
};
Mesh generate_sphere_octant(const SphereOctantSpec& spec);

// Writes the geometry above as a .msh 4.1 file (binary or ASCII), for tests and users.
void write_box_msh(int dim, const std::array<double, 3>& lengths, double h,
                   const std::string& path, bool binary);

}  // namespace stiction::mesh
