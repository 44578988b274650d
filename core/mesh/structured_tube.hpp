#pragma once
// A structured tetrahedral mesh of a tube sector: the ring between two radii, between two
// angles, along a straight axis. Made as structured_box's Kuhn-split hexahedra in
// (radius, angle, axial) coordinates, mapped so that every vertex lies on the true cylinders,
// and every edge that the map bends carries its true midpoint (Mesh::edge_midpoints), so
// that P2 cells are curved. A refined level is a new mesh with 2^level times the cells, so
// refined vertices stay on the cylinders too.
#include <array>
#include <limits>

#include "mesh/mesh.hpp"

namespace stiction::mesh {

struct TubeSpec {
  double inner_radius = 0, thickness = 0, length = 0;
  int axis = 2;                                  // 0 x, 1 y, 2 z
  std::array<double, 3> center{0, 0, 0};         // on the axis, at the start face
  std::array<double, 2> angles_degrees{0, 360};  // around the axis, from a towards b (below)
  std::array<int, 3> cells{2, 24, 16};           // through the thickness, around, along
  // An angle strictly between the two: the inner cylinder is named in two halves, "inner0"
  // (from angles_degrees[0] to it) and "inner1" (from it on), so that a tube that flattens
  // can take its inner walls as a self-contact pair. NaN: one face "inner".
  double inner_split_degrees = std::numeric_limits<double>::quiet_NaN();
};

// Angles are measured in the plane normal to the axis from the next axis in cyclic order
// towards the one after it: axis x: from y towards z; y: from z towards x; z: from x
// towards y. Facet names: "inner" (or "inner0", "inner1"), "outer" (the cylinders), "side0",
// "side1" (the faces at the two angles), "start" (at center), "end" (length along the axis).
// Cell tag "body". A facet of the inner cylinder belongs to the half holding its centroid.
Mesh structured_tube(const TubeSpec& spec);

}  // namespace stiction::mesh
